#pragma once
// `wavebench simbench` as its own process for the vcan tests: spawned on an interface with a
// bench config (its simulated devices) and a free loopback port for its brake, waited for until
// that port accepts, ended with SIGTERM when the object goes.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace wavebench::testing {

inline int free_tcp_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  ::close(fd);
  return ntohs(addr.sin_port);
}

inline bool tcp_port_accepts(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  const bool ok = fd >= 0 && ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
  if (fd >= 0) ::close(fd);
  return ok;
}

class SimbenchProcess {
 public:
  SimbenchProcess() = default;
  SimbenchProcess(const SimbenchProcess&) = delete;
  SimbenchProcess& operator=(const SimbenchProcess&) = delete;
  ~SimbenchProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
  }

  // Empty when it runs and its brake port accepts; otherwise what went wrong.
  std::string start(const std::string& interface, const std::string& bench_config) {
    port_ = free_tcp_port();
    if (port_ <= 0) return "no free loopback port";
    const std::string exe = std::string(WAVEBENCH_BINARY_DIR) + "/src/cli/wavebench";
    std::vector<std::string> args{exe,
                                  "simbench",
                                  "--can",
                                  interface,
                                  "--clock",
                                  "sync",
                                  "--bench-config",
                                  bench_config,
                                  "--modbus",
                                  "tcp:127.0.0.1:" + std::to_string(port_),
                                  "--duration",
                                  "1800"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
      pid_ = -1;
      return "cannot start " + exe;
    }
    // Emulated and loaded: wait for the brake port generously; the nodes boot with it.
    using namespace std::chrono_literals;
    const auto deadline = std::chrono::steady_clock::now() + 120s;
    while (!tcp_port_accepts(port_) && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(100ms);
    if (!tcp_port_accepts(port_))
      return "simbench's brake port " + std::to_string(port_) + " never opened";
    return {};
  }

  int port() const noexcept { return port_; }

 private:
  int port_ = -1;
  pid_t pid_ = -1;
};

}  // namespace wavebench::testing
