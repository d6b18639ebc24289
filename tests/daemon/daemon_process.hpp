#pragma once
// wavebenchd as a child process for the integration tests: started with arguments, its
// "listening on" line read from stdout for the port, stderr kept in a file.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace wavebench::daemon::testing {

class DaemonProcess {
 public:
  DaemonProcess(const std::vector<std::string>& args, const std::filesystem::path& stderr_file)
      : stderr_file_(stderr_file) {
    int out[2];
    if (::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], STDOUT_FILENO);
      const int err = ::open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, STDERR_FILENO);
      ::close(out[0]);
      std::vector<char*> argv;
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      _exit(127);
    }
    ::close(out[1]);
    stdout_ = ::fdopen(out[0], "r");
  }
  ~DaemonProcess() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (stdout_) std::fclose(stdout_);
  }
  DaemonProcess(const DaemonProcess&) = delete;
  DaemonProcess& operator=(const DaemonProcess&) = delete;

  // The port from "wavebenchd: listening on http://HOST:PORT"; 0 when the daemon ended first.
  int wait_for_port() {
    char line[512];
    while (stdout_ && std::fgets(line, sizeof line, stdout_)) {
      const std::string text = line;
      const auto at = text.find("listening on http://");
      if (at == std::string::npos) continue;
      const auto colon = text.rfind(':');
      return std::stoi(text.substr(colon + 1));
    }
    return 0;
  }
  void signal(int number) const { ::kill(pid_, number); }
  // The wait status.
  int wait() {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    reaped_ = true;
    return status;
  }
  std::string stderr_text() const {
    std::ifstream in(stderr_file_);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  pid_t pid() const { return pid_; }

 private:
  std::filesystem::path stderr_file_;
  pid_t pid_ = -1;
  FILE* stdout_ = nullptr;
  bool reaped_ = false;
};

}  // namespace wavebench::daemon::testing
