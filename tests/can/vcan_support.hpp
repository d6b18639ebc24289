#pragma once
// Helpers for the tests that need a real SocketCAN vcan0 (inside scripts/vcan-vm/); elsewhere
// they skip. Every wait is for something already caused; the limits only guard against hangs.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <net/if.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace wavebench::testing {

inline constexpr const char* kVcan = "vcan0";

inline bool vcan_available() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, 1 /* CAN_RAW */);
  if (fd < 0) return false;
  ::close(fd);
  return if_nametoindex(kVcan) != 0;
}

#define WAVEBENCH_REQUIRE_VCAN()                                                          \
  do {                                                                                    \
    if (!::wavebench::testing::vcan_available()) {                                        \
      GTEST_SKIP() << "vcan0 is absent; run scripts/vcan-vm/run-vcan-tests.sh BUILD_DIR"; \
    }                                                                                     \
  } while (false)

// Runs the io_context until `done()` or the guard limit; returns done().
template <typename Pred>
bool run_until(boost::asio::io_context& io, Pred done,
               std::chrono::seconds limit = std::chrono::seconds(120)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (!done() && std::chrono::steady_clock::now() < end) {
    if (io.stopped()) io.restart();
    io.run_one_for(std::chrono::milliseconds(20));
  }
  return done();
}

// Receivers registered on the interface (all /proc/net/can/rcvlist_*): grows when a new socket
// (candump, python-can) binds, so the test knows it listens before sending.
inline int registered_receivers(const std::string& ifname = kVcan) {
  int count = 0;
  for (const char* list : {"all", "fil", "inv", "sff", "eff", "err"}) {
    std::ifstream in(std::string("/proc/net/can/rcvlist_") + list);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string first;
      words >> first;
      if (first == ifname) ++count;
    }
  }
  return count;
}

// A child process with stdout+stderr to a file, stopped by signal or awaited.
class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& argv, std::string output_path)
      : output_path_(std::move(output_path)) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const int fd = ::open(output_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        ::dup2(fd, 1);
        ::dup2(fd, 2);
      }
      std::vector<char*> args;
      for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      ::execvp(args[0], args.data());
      ::_exit(127);
    }
  }
  ~ChildProcess() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ > 0; }
  int stop(int sig = SIGTERM) {
    if (pid_ <= 0 || reaped_) return -1;
    ::kill(pid_, sig);
    return wait();
  }
  int wait() {
    if (!reaped_) {
      ::waitpid(pid_, &status_, 0);
      reaped_ = true;
    }
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }
  bool exited() {
    if (reaped_) return true;
    if (::waitpid(pid_, &status_, WNOHANG) == pid_) reaped_ = true;
    return reaped_;
  }
  std::string output() const {
    std::ifstream in(output_path_);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = 0;
  std::string output_path_;
};

// candump -L lines without the "(timestamp) " prefix: "vcan0 601#4018100100000000".
inline std::vector<std::string> candump_frames(const std::string& output) {
  std::vector<std::string> out;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    const auto close = line.find(") ");
    if (line.empty() || line[0] != '(' || close == std::string::npos) continue;
    out.push_back(line.substr(close + 2));
  }
  return out;
}

}  // namespace wavebench::testing
