// wavebenchd refuses to start on a weak credential or an exposed address, with the reason and
// exit 2, before it creates anything; the `wavebench` client gives up on a silent server and
// refuses an answer that is not the daemon's JSON.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "test_dir.hpp"

namespace wavebench::daemon::testing {
namespace {

namespace fs = std::filesystem;

struct Exit {
  int code = -1;
  std::string stderr_text;
};

Exit run_daemon(const std::vector<std::string>& args, const fs::path& dir) {
  std::vector<std::string> argv = {WAVEBENCHD_PATH, "--config", "simulated"};
  argv.insert(argv.end(), args.begin(), args.end());
  DaemonProcess p(argv, dir / "stderr.txt");
  // A daemon that wrongly starts is stopped: the port line means it listened.
  if (p.wait_for_port() != 0) p.signal(SIGTERM);
  const int status = p.wait();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, p.stderr_text()};
}

void write_file(const fs::path& path, const std::string& text, mode_t mode) {
  std::ofstream(path) << text;
  ::chmod(path.c_str(), mode);
}

TEST(HostileDaemonStart, AWeakTokenFileIsRefusedWithTheReasonAndExit2) {
  const auto dir = fresh_test_dir();
  // A token file's content and mode, or a folder / FIFO in its place; what the refusal says.
  enum class Kind { kFile, kFolder, kFifo };
  struct Case {
    std::string name;
    Kind kind;
    std::string content;
    mode_t mode;
    std::string expected_words;
  };
  const std::string good = "0123456789abcdef0123456789abcdef\n";
  const std::vector<Case> cases = {
      {"world-readable", Kind::kFile, good, 0644, "mode 0644"},
      {"group-writable", Kind::kFile, good, 0620, "mode 0620"},
      {"three characters", Kind::kFile, "abc\n", 0600, "3 characters"},
      {"a folder", Kind::kFolder, "", 0700, "not a regular file"},
      {"a FIFO (must not block)", Kind::kFifo, "", 0600, "not a regular file"},
      {"blank", Kind::kFile, "  \n\n", 0600, "empty"},
      {"two words", Kind::kFile, "0123456789abcdef 0123456789abcdef\n", 0600, "printable"},
      {"too large", Kind::kFile, std::string(100000, 'a'), 0600, "at most 4096 bytes"},
  };
  int refused = 0;
  for (const auto& c : cases) {
    const auto path = dir / ("token-" + std::to_string(&c - cases.data()));
    if (c.kind == Kind::kFile) write_file(path, c.content, c.mode);
    if (c.kind == Kind::kFolder) fs::create_directories(path);
    if (c.kind == Kind::kFifo) ::mkfifo(path.c_str(), c.mode);
    const auto runs = dir / ("runs-" + std::to_string(refused));
    const auto e = run_daemon(
        {"--runs", runs.string(), "--listen", "127.0.0.1:0", "--token-file", path.string()}, dir);
    EXPECT_EQ(e.code, 2) << c.name << ": " << e.stderr_text;
    EXPECT_NE(e.stderr_text.find(c.expected_words), std::string::npos)
        << c.name << ": " << e.stderr_text;
    EXPECT_NE(e.stderr_text.find(path.string()), std::string::npos) << c.name;
    EXPECT_FALSE(fs::exists(runs)) << c.name << ": nothing may be created";
    refused += e.code == 2 ? 1 : 0;
  }
  std::printf("[ hostile  ] %zu weak token files, %d refused with exit 2\n", cases.size(), refused);
}

TEST(HostileDaemonStart, AListenAddressBeyondLoopbackNeedsAllowRemote) {
  const auto dir = fresh_test_dir();
  write_file(dir / "token", "0123456789abcdef0123456789abcdef\n", 0600);
  const std::vector<std::string> addresses = {"0.0.0.0:0",   "[::]:0",        "192.0.2.1:0",
                                              "localhost:0", "example.org:0", "127.0.0.1:70000"};
  int refused = 0;
  for (const auto& address : addresses) {
    const auto e = run_daemon({"--runs", (dir / "runs").string(), "--listen", address,
                               "--token-file", (dir / "token").string()},
                              dir);
    EXPECT_EQ(e.code, 2) << address << ": " << e.stderr_text;
    EXPECT_NE(e.stderr_text.find("--listen"), std::string::npos) << e.stderr_text;
    refused += e.code == 2 ? 1 : 0;
  }
  EXPECT_FALSE(fs::exists(dir / "runs"));
  std::printf("[ hostile  ] %zu listen addresses beyond loopback or not IP, %d refused\n",
              addresses.size(), refused);
}

// A TCP server on loopback that either never answers or answers something that is not the
// daemon's JSON.
class FakeServer {
 public:
  explicit FakeServer(std::string reply) : reply_(std::move(reply)) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    ::listen(fd_, 16);
    socklen_t len = sizeof addr;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~FakeServer() {
    stop_ = true;
    ::shutdown(fd_, SHUT_RDWR);
    ::close(fd_);
    thread_.join();
    for (const int c : clients_) ::close(c);
  }
  unsigned short port() const { return port_; }

 private:
  void serve() {
    while (!stop_) {
      const int c = ::accept(fd_, nullptr, nullptr);
      if (c < 0) return;
      clients_.push_back(c);  // held open, unanswered, when reply_ is empty
      if (!reply_.empty()) {
        char buffer[4096];
        (void)::recv(c, buffer, sizeof buffer, 0);
        (void)::send(c, reply_.data(), reply_.size(), MSG_NOSIGNAL);
        ::shutdown(c, SHUT_WR);
      }
    }
  }
  std::string reply_;
  int fd_ = -1;
  unsigned short port_ = 0;
  std::atomic<bool> stop_{false};
  std::vector<int> clients_;
  std::thread thread_;
};

Exit run_client(const std::string& args, const fs::path& dir) {
  const auto log = dir / "client.txt";
  const std::string cmd =
      std::string("'") + WAVEBENCH_CLI_PATH + "' " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

TEST(HostileDaemonClient, ASilentServerOrOneThatIsNotTheDaemonIsAnErrorNotAHang) {
  const auto dir = fresh_test_dir();
  write_file(dir / "token", "0123456789abcdef0123456789abcdef\n", 0600);
  FakeServer silent("");
  FakeServer html(
      "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nContent-Length: 13\r\n\r\n<html></html>");
  FakeServer array("HTTP/1.1 200 OK\r\nContent-Length: 2\r\n\r\n[]");
  FakeServer garbage("SSH-2.0-OpenSSH_9.2\r\n");
  const std::vector<std::string> commands = {"status", "abort", "stop",
                                             "reset",  "runs",  "start static"};
  int errors = 0;
  int tried = 0;
  for (const auto* server : {&silent, &html, &array, &garbage}) {
    for (const auto& command : commands) {
      const auto started = std::chrono::steady_clock::now();
      const auto e =
          run_client(command + " --daemon http://127.0.0.1:" + std::to_string(server->port()) +
                         " --timeout 1 --token-file " + (dir / "token").string(),
                     dir);
      const auto took = std::chrono::steady_clock::now() - started;
      ++tried;
      EXPECT_EQ(e.code, 1) << command << ": " << e.stderr_text;
      EXPECT_NE(e.stderr_text.find("wavebench:"), std::string::npos) << e.stderr_text;
      // A guard against a hang, far above the 1 s asked for: not a timing assertion.
      EXPECT_LT(took, std::chrono::seconds(30)) << command;
      errors += e.code == 1 ? 1 : 0;
    }
  }
  const auto silent_status = run_client(
      "status --daemon http://127.0.0.1:" + std::to_string(silent.port()) + " --timeout 1", dir);
  EXPECT_NE(silent_status.stderr_text.find("no answer within 1000 ms"), std::string::npos)
      << silent_status.stderr_text;
  const auto html_status = run_client(
      "status --daemon http://127.0.0.1:" + std::to_string(html.port()) + " --timeout 1", dir);
  EXPECT_NE(html_status.stderr_text.find("not the daemon's JSON"), std::string::npos)
      << html_status.stderr_text;
  std::printf("[ hostile  ] %d client commands against silent or foreign servers, %d exit 1\n",
              tried, errors);
}

}  // namespace
}  // namespace wavebench::daemon::testing
