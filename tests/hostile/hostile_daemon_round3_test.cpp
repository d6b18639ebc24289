// Issue #22, the daemon's HTTP side, through real wavebenchd processes on loopback:
//  6  two daemons on one PC keep separate sessions (one cookie jar logs in to both);
//  7  export downloads in bounded memory and scratch, at most two at once, /api/status answered
//     while two run, a login needed;
//  8  live-stream clients that never read lose their slots; the CLI's client retries "busy";
// 10  fleet parameters: unknown keys, RFC 3339 times, enumerations refused with 400;
// 11  failed logins rate-limited and logged (client, sanitised name, never the password).
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "raw_http.hpp"
#include "test_dir.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {
namespace {

namespace fs = std::filesystem;
using wavebench::testing::get_request;
using wavebench::testing::raw_http;
using Clock = std::chrono::steady_clock;
constexpr const char* kTokenText = "0123456789abcdef0123456789abcdef";

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// A wavebenchd on the simulated bench with its own runs folder, token and TMPDIR.
struct Daemon {
  explicit Daemon(const fs::path& dir) : dir_(dir) {
    fs::create_directories(dir / "tmp");
    std::ofstream(dir / "token") << kTokenText << "\n";
    ::chmod((dir / "token").c_str(), 0600);
    ::setenv("TMPDIR", (dir / "tmp").c_str(), 1);  // inherited by the child: its scratch
    process = std::make_unique<DaemonProcess>(
        std::vector<std::string>{WAVEBENCHD_PATH, "--config", "sim", "--runs",
                                 (dir / "runs").string(), "--listen", "127.0.0.1:0", "--token-file",
                                 (dir / "token").string()},
        dir / "stderr.txt");
    ::unsetenv("TMPDIR");
    port = process->wait_for_port();
  }
  std::string host() const { return "127.0.0.1:" + std::to_string(port); }
  std::string url() const { return "http://" + host(); }
  // A raw request with the console's header and a cookie jar.
  wavebench::testing::RawReply send(const std::string& method, const std::string& target,
                                    const std::string& cookie, const std::string& body = "",
                                    std::string* set_cookie = nullptr) const {
    std::string text =
        method + " " + target + " HTTP/1.1\r\nHost: " + host() +
        "\r\nX-Wavebench-Request: console\r\nCookie: " + cookie +
        "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
        "\r\nConnection: close\r\n\r\n" + body;
    auto reply = raw_http(static_cast<unsigned short>(port), text);
    (void)set_cookie;
    return reply;
  }
  long rss_kib() const { return proc_status_kib("VmRSS:"); }
  long proc_status_kib(const std::string& key) const {
    std::ifstream in("/proc/" + std::to_string(process->pid()) + "/status");
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + key.size());
    }
    return -1;
  }
  std::uintmax_t scratch_bytes() const {
    std::uintmax_t total = 0;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir_ / "tmp", ec), end; !ec && it != end;
         it.increment(ec)) {
      if (it->is_regular_file(ec)) total += it->file_size(ec);
    }
    return total;
  }

  fs::path dir_;
  std::unique_ptr<DaemonProcess> process;
  int port = 0;
};

int connect_loopback(int port, int rcvbuf = 0) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (rcvbuf > 0) ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  timeval tv{10, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<unsigned short>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void send_all(int fd, const std::string& text) {
  std::size_t sent = 0;
  while (sent < text.size()) {
    const auto n = ::send(fd, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return;
    sent += static_cast<std::size_t>(n);
  }
}

// Reads until the header's end; the header text (status line first).
std::string read_header(int fd) {
  std::string text;
  char c;
  while (text.find("\r\n\r\n") == std::string::npos && ::recv(fd, &c, 1, 0) == 1) text += c;
  return text;
}

// The Set-Cookie name=value of a login answer, from its raw header.
std::string login_cookie(const Daemon& d) {
  const int fd = connect_loopback(d.port);
  const std::string body = std::string(R"({"token": ")") + kTokenText + "\"}";
  send_all(fd, "POST /api/session HTTP/1.1\r\nHost: " + d.host() +
                   "\r\nX-Wavebench-Request: console\r\nContent-Type: application/json\r\n"
                   "Content-Length: " +
                   std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body);
  const auto header = read_header(fd);
  ::close(fd);
  const auto at = header.find("Set-Cookie: ");
  if (at == std::string::npos) return {};
  const auto start = at + 12;
  return header.substr(start, header.find(';', start) - start);
}

// Item 6: one browser (one cookie jar) logged in to two daemons on one PC.
TEST(HostileDaemonRound3, TwoDaemonsOnOnePcKeepTheirOwnSessions) {
  const auto dir = fresh_test_dir();
  Daemon a(dir / "a");
  Daemon b(dir / "b");
  ASSERT_GT(a.port, 0) << a.process->stderr_text();
  ASSERT_GT(b.port, 0) << b.process->stderr_text();
  // Browsers keep cookies per host, not per port: both land in one jar.
  std::map<std::string, std::string> jar;
  for (const auto* d : {&a, &b}) {
    const auto cookie = login_cookie(*d);
    ASSERT_FALSE(cookie.empty());
    jar[cookie.substr(0, cookie.find('='))] = cookie.substr(cookie.find('=') + 1);
  }
  EXPECT_EQ(jar.size(), 2u) << "the second login overwrote the first's cookie";
  std::string cookie_header;
  for (const auto& [name, value] : jar) cookie_header += name + "=" + value + "; ";
  for (const auto* d : {&a, &b}) {
    const auto session = d->send("GET", "/api/session", cookie_header);
    EXPECT_EQ(session.json.value("authenticated", false), true) << session.body;
    // A change that needs the session (abort: the console's own rule) is not refused 401.
    const auto abort = d->send("POST", "/api/abort", cookie_header, "{}");
    EXPECT_NE(abort.status, 401) << abort.body;
    const auto stop = d->send("POST", "/api/stop", cookie_header, "{}");
    EXPECT_EQ(stop.status, 200) << stop.body;
  }
  std::printf("[ hostile  ] two daemons (ports %d, %d), one cookie jar: cookies %s\n", a.port,
              b.port, cookie_header.substr(0, 40).c_str());
}

// A finished run with `records` samples, made straight in the store before the daemon starts.
std::string stored_run(const fs::path& runs, std::uint64_t records) {
  storage::RunStore store(runs, "test");
  const auto id = store.create_run("dynamic", "U-22", "config: test\n");
  {
    storage::SampleLogWriterOptions options;
    options.checkpoint_every_records = 0;
    options.flush_every_records = 4096;
    storage::SampleLogWriter log(store.paths(id).samples, options);
    storage::SyncSample s;
    for (std::uint64_t i = 0; i < records; ++i) {
      s.sync_counter = static_cast<std::uint32_t>(i % 65535 + 1);
      s.flags = storage::kAllChannelsValid;
      s.receive_time_ns = static_cast<std::int64_t>(i) * 1000000;
      s.theta_in_rad = 0.001 * static_cast<double>(i);
      s.theta_out_rad = s.theta_in_rad / 100;
      s.torque_nm = 12.5;
      log.append(s);
    }
    log.close();
  }
  store.finish_run(id, storage::RunStatus::kComplete, "", true);
  return id;
}

struct Download {
  int status = 0;
  std::uint64_t bytes = 0;
  bool complete = false;  // the chunked body's last chunk came
};

Download download(int port, const std::string& target, const std::string& auth) {
  Download d;
  const int fd = connect_loopback(port);
  send_all(fd, get_request(target, "127.0.0.1:" + std::to_string(port), auth));
  const auto header = read_header(fd);
  if (header.size() > 12) d.status = std::atoi(header.c_str() + 9);
  std::string tail;
  char buffer[1 << 16];
  for (;;) {
    const auto n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    d.bytes += static_cast<std::uint64_t>(n);
    tail.append(buffer, static_cast<std::size_t>(n));
    if (tail.size() > 16) tail.erase(0, tail.size() - 16);
  }
  ::close(fd);
  d.complete = tail.size() >= 5 && tail.substr(tail.size() - 5) == "0\r\n\r\n";
  return d;
}

// Item 7: downloads of a large log cost a bounded amount of memory and scratch, two at most at
// once, and /api/status stays quick while two run.
TEST(HostileDaemonRound3, DownloadsAreStreamedBoundedAndLimitedAndStatusStaysQuick) {
  const auto dir = fresh_test_dir();
  // 55 MiB by default; WAVEBENCH_DOWNLOAD_TEST_RECORDS=2770000 gives the issue's 254 MB log.
  const char* scale = std::getenv("WAVEBENCH_DOWNLOAD_TEST_RECORDS");
  const std::uint64_t records = scale ? std::strtoull(scale, nullptr, 10) : 600000;
  const auto id = stored_run(dir / "d" / "runs", records);
  Daemon d(dir / "d");
  ASSERT_GT(d.port, 0) << d.process->stderr_text();
  const auto log_bytes = fs::file_size(dir / "d" / "runs" / id / "samples.wbs");
  const std::string auth = std::string("Authorization: Bearer ") + kTokenText + "\r\n";
  const auto target = [&](const char* format) {
    return "/api/runs/" + id + "/export?format=" + format;
  };

  // No login: refused before anything is read.
  EXPECT_EQ(download(d.port, target("csv"), "").status, 401);

  // Watch memory, scratch and /api/status while two downloads run.
  std::atomic<bool> watching{true};
  long rss_before = d.rss_kib(), rss_peak = rss_before;
  std::uintmax_t scratch_peak = 0;
  std::vector<double> status_ms;
  std::thread watcher([&] {
    while (watching) {
      const auto t0 = Clock::now();
      const auto s =
          raw_http(static_cast<unsigned short>(d.port), get_request("/api/status", d.host()));
      if (s.status == 200) status_ms.push_back(ms_since(t0));
      rss_peak = std::max(rss_peak, d.rss_kib());
      scratch_peak = std::max(scratch_peak, d.scratch_bytes());
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  const auto measure = [&](const char* format) {
    rss_before = d.rss_kib();
    rss_peak = rss_before;
    scratch_peak = 0;
    status_ms.clear();
    const auto t0 = Clock::now();
    Download one, two;
    std::thread first([&] { one = download(d.port, target(format), auth); });
    std::thread second([&] { two = download(d.port, target(format), auth); });
    first.join();
    second.join();
    const double took = ms_since(t0);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::vector<double> sorted = status_ms;
    std::sort(sorted.begin(), sorted.end());
    const double worst = sorted.empty() ? -1 : sorted.back();
    const double median = sorted.empty() ? -1 : sorted[sorted.size() / 2];
    std::printf(
        "[ hostile  ] 2 x %s download of a %.1f MiB log (%llu samples): %.1f MiB each in %.0f ms; "
        "daemon RSS %+.1f MiB at peak; scratch peak %.1f MiB; /api/status %zu answers, median "
        "%.1f ms, max %.1f ms\n",
        format, static_cast<double>(log_bytes) / 1048576.0,
        static_cast<unsigned long long>(records), static_cast<double>(one.bytes) / 1048576.0, took,
        static_cast<double>(rss_peak - rss_before) / 1024.0,
        static_cast<double>(scratch_peak) / 1048576.0, sorted.size(), median, worst);
    EXPECT_EQ(one.status, 200);
    EXPECT_EQ(two.status, 200);
    EXPECT_TRUE(one.complete && two.complete) << format;
    EXPECT_GT(one.bytes, log_bytes / 2) << format;
    // Memory: a page of samples per download, not the file (which is several times this).
    EXPECT_LT(rss_peak - rss_before, 160 * 1024) << format;
    EXPECT_FALSE(sorted.empty());
    EXPECT_LT(worst, 1000.0) << format << ": /api/status stalled";
    return scratch_peak;
  };
  const auto csv_scratch = measure("csv");
  EXPECT_EQ(csv_scratch, 0u) << "csv is streamed: no scratch file";
  const auto h5_scratch = measure("hdf5");
  EXPECT_LE(h5_scratch, 2 * log_bytes + (16u << 20)) << "one scratch file per download";
  watching = false;
  watcher.join();
  EXPECT_EQ(d.scratch_bytes(), 0u) << "scratch left behind";

  // A third download while two are held open by clients that read slowly: 503 + Retry-After.
  std::vector<int> held;
  for (int i = 0; i < 2; ++i) {
    const int fd = connect_loopback(d.port, 4096);
    send_all(fd, get_request(target("csv"), d.host(), auth));
    EXPECT_NE(read_header(fd).find(" 200 "), std::string::npos);
    held.push_back(fd);
  }
  const int third = connect_loopback(d.port);
  send_all(third, get_request(target("csv"), d.host(), auth));
  const auto refused = read_header(third);
  ::close(third);
  EXPECT_NE(refused.find(" 503 "), std::string::npos) << refused;
  EXPECT_NE(refused.find("Retry-After: 5"), std::string::npos) << refused;
  for (const int fd : held) ::close(fd);
  // Their slots come back once the clients have gone.
  bool freed = false;
  for (int i = 0; i < 100 && !freed; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const int fd = connect_loopback(d.port);
    send_all(fd, get_request(target("json"), d.host(), auth));
    freed = read_header(fd).find(" 200 ") != std::string::npos;
    ::close(fd);
  }
  EXPECT_TRUE(freed) << "download slots not freed after the clients closed";
}

// Item 8: eight clients that open the live stream and never read held every slot for minutes.
// Each is now dropped once it has left data unread for kStalledReaderLimit (10 s), and the
// console's own stream is served again.
TEST(HostileDaemonRound3, LiveStreamClientsThatNeverReadLoseTheirSlots) {
  const auto dir = fresh_test_dir();
  Daemon d(dir / "d");
  ASSERT_GT(d.port, 0) << d.process->stderr_text();
  const auto stream_request = get_request("/api/live/stream", d.host());
  std::vector<int> idle;
  for (int i = 0; i < 8; ++i) {
    // A small receive buffer, as a client far away or on a slow link has: it fills in seconds.
    const int fd = connect_loopback(d.port, 8192);
    ASSERT_GE(fd, 0);
    send_all(fd, stream_request);
    idle.push_back(fd);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  const auto t0 = Clock::now();
  const auto full = raw_http(static_cast<unsigned short>(d.port), stream_request, 2);
  EXPECT_EQ(full.status, 503) << "all 8 slots should be taken";
  int status = 0;
  std::string events;
  while (ms_since(t0) < 60000) {
    const int fd = connect_loopback(d.port);
    send_all(fd, stream_request);
    const auto header = read_header(fd);
    status = header.size() > 12 ? std::atoi(header.c_str() + 9) : 0;
    if (status == 200) {
      char buffer[4096];
      const auto n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n > 0) events.assign(buffer, static_cast<std::size_t>(n));
      ::close(fd);
      break;
    }
    ::close(fd);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  const double waited = ms_since(t0);
  for (const int fd : idle) ::close(fd);
  std::printf(
      "[ hostile  ] 8 live-stream clients that never read: a new stream served after "
      "%.1f s\n",
      waited / 1000.0);
  EXPECT_EQ(status, 200);
  EXPECT_NE(events.find("data:"), std::string::npos) << events;
  EXPECT_LT(waited, 40000.0);
  EXPECT_NE(d.process->stderr_text().find("read nothing"), std::string::npos);
}

// Item 8: a read refused 503 "busy" is retried after Retry-After, for a bounded time, saying
// what it waits for. A fake daemon answers busy twice, then the answer.
TEST(HostileDaemonRound3, TheClientRetriesBusyAnswersForABoundedTime) {
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  ASSERT_EQ(::listen(listener, 8), 0);
  socklen_t len = sizeof addr;
  ::getsockname(listener, reinterpret_cast<sockaddr*>(&addr), &len);
  const int port = ntohs(addr.sin_port);
  std::atomic<int> busy_answers{2};
  std::atomic<int> served{0};
  std::atomic<bool> serving{true};
  std::thread server([&] {
    while (serving) {
      const int fd = ::accept(listener, nullptr, nullptr);
      if (fd < 0) return;
      if (!serving) {
        ::close(fd);
        return;
      }
      (void)read_header(fd);
      ++served;
      const bool busy = busy_answers-- > 0;
      const std::string body =
          busy ? R"({"error":"busy","detail":"2 reads of run data"})" : R"({"state":"ready"})";
      send_all(fd, std::string(busy ? "HTTP/1.1 503 Service Unavailable\r\nRetry-After: 1\r\n"
                                    : "HTTP/1.1 200 OK\r\n") +
                       "Content-Type: application/json\r\nContent-Length: " +
                       std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body);
      ::close(fd);
    }
  });
  DaemonClient client("http://127.0.0.1:" + std::to_string(port), "");
  std::vector<std::string> notices;
  client.retry_busy(std::chrono::seconds(10),
                    [&](const std::string& what) { notices.push_back(what); });
  auto t0 = Clock::now();
  const auto reply = client.get("/api/runs/x/samples");
  const double waited = ms_since(t0);
  EXPECT_EQ(reply.status, 200);
  EXPECT_EQ(served.load(), 3);
  ASSERT_EQ(notices.size(), 2u);
  EXPECT_NE(notices[0].find("busy"), std::string::npos) << notices[0];
  EXPECT_NE(notices[0].find("/api/runs/x/samples"), std::string::npos) << notices[0];
  EXPECT_GE(waited, 1900.0);  // Retry-After: 1, twice
  // Bounded: a daemon busy for ever is given up after the wait, and its 503 reported.
  busy_answers = 1000;
  client.retry_busy(std::chrono::seconds(3), [](const std::string&) {});
  t0 = Clock::now();
  EXPECT_EQ(client.get("/api/status").status, 503);
  const double gave_up = ms_since(t0);
  EXPECT_LT(gave_up, 4500.0);
  EXPECT_GE(gave_up, 1900.0);
  std::printf(
      "[ hostile  ] busy twice then served: %.0f ms, 2 notices; busy for ever: gave up "
      "after %.0f ms\n",
      waited, gave_up);
  serving = false;
  const int poke = connect_loopback(port);
  if (poke >= 0) ::close(poke);
  server.join();
  ::close(listener);
}

// Items 10 and 11 on one daemon: fleet parameters, and failed logins throttled and logged.
TEST(HostileDaemonRound3, FleetParametersAreCheckedAndFailedLoginsAreLogged) {
  const auto dir = fresh_test_dir();
  Daemon d(dir / "d");
  ASSERT_GT(d.port, 0) << d.process->stderr_text();
  const DaemonClient client(d.url(), kTokenText);
  struct Case {
    std::string query;
    std::string named;  // what the 400's detail must name
  };
  const std::vector<Case> refused = {
      // A leap second where none is inserted (22:59:60 UTC), and a year past 9999 in UTC.
      {"/api/fleet/runs?from=9999-12-31T23:59:60%2B01:00", "leap second"},
      {"/api/fleet/runs?from=9999-12-31T23:59:59-01:00", "year 1000 to 9999"},
      {"/api/fleet/runs?from=2026-11-24T10:00:00%2B24:00", "-23:59 to +23:59"},
      {"/api/fleet/runs?to=2026-11-24T10:00:00-00:60", "from"},
      {"/api/fleet/runs?from=2026-11-24T12:30:60Z", "leap second"},
      {"/api/fleet/runs?from=0999-01-01", "from"},
      {"/api/fleet/runs?status=complete", "'status'"},
      {"/api/fleet/runs?spec=SG-1", "'spec'"},
      {"/api/fleet/runs?modle=X", "'modle'"},
      {"/api/fleet/runs?verdict=maybe", "PASS, FAIL or UNDECIDED"},
      {"/api/fleet/trend?figure=static_te_p2p&model=M&direction=sideways", "forward or reverse"},
      {"/api/fleet/spc?figure=static_te_p2p&model=M&lsl=1&usl=2&colour=red", "'colour'"},
      {"/api/fleet/figures?x=1", "'x'"},
  };
  int n400 = 0;
  for (const auto& c : refused) {
    const auto reply = client.get(c.query);
    EXPECT_EQ(reply.status, 400) << c.query << ": " << reply.body.dump();
    EXPECT_NE(reply.error_text().find(c.named), std::string::npos)
        << c.query << ": " << reply.error_text();
    n400 += reply.status == 400;
  }
  // What RFC 3339 allows still works.
  // 9999-12-31T23:59:60Z is a legal leap second: it sorts after every run (it returned every
  // run when it became "10000-01-01", text before "2026-").
  const auto last_second = client.get("/api/fleet/runs?from=9999-12-31T23:59:60Z");
  EXPECT_EQ(last_second.status, 200);
  EXPECT_TRUE(last_second.body["runs"].empty()) << last_second.body.dump().substr(0, 300);
  for (const auto* ok : {"/api/fleet/runs?from=2016-12-31T23:59:60Z",
                         "/api/fleet/runs?from=2026-11-24T10:00:00%2B23:59&verdict=pass",
                         "/api/fleet/runs?to=9999-12-31T23:59:59Z&limit=5", "/api/fleet/figures"}) {
    EXPECT_EQ(client.get(ok).status, 200) << ok << ": " << client.get(ok).body.dump();
  }
  std::printf("[ hostile  ] %zu bad fleet queries, %d refused with 400 naming the key\n",
              refused.size(), n400);

  // Item 11: wrong passwords and tokens are throttled (429 + Retry-After) and logged.
  const std::string secret = "hunter2-secret-password";
  int failed = 0, throttled = 0;
  for (int i = 0; i < 12; ++i) {
    const auto body = i % 2 ? R"({"name": "mallory", "password": ")" + secret + "\"}"
                            : R"({"token": "wrong-token-0123456789-)" + secret + "\"}";
    const auto reply = d.send("POST", "/api/session", "", body);
    failed += reply.status == 401;
    throttled += reply.status == 429;
  }
  // Five free failures per client, then a lockout that doubles with each further failure.
  EXPECT_LE(failed, 6);
  EXPECT_GE(throttled, 6) << "failed logins are not rate-limited";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the log is asynchronous
  const auto log = d.process->stderr_text();
  EXPECT_NE(log.find("login failed for account 'mallory' from 127.0.0.1"), std::string::npos)
      << log.substr(0, 3000);
  EXPECT_NE(log.find("login failed for the token from 127.0.0.1"), std::string::npos);
  EXPECT_NE(log.find("throttled"), std::string::npos);
  EXPECT_EQ(log.find(secret), std::string::npos) << "a password reached the log";
  std::printf(
      "[ hostile  ] 12 bad logins: %d answered 401, %d throttled 429; all logged, no "
      "password in the log\n",
      failed, throttled);
}

}  // namespace
}  // namespace wavebench::daemon::testing
