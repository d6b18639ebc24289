// Hostile and careless HTTP requests against an in-process daemon (fake bench, fake executor)
// over real sockets: every one gets an HTTP error answer with a JSON body, the daemon keeps
// answering, nothing starts and nothing trips.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "daemon_fixture.hpp"
#include "raw_http.hpp"
#include "wavebench/daemon/last_resort_guard.hpp"

namespace wavebench::daemon::testing {
namespace {

using wavebench::testing::get_request;
using wavebench::testing::post_request;
using wavebench::testing::raw_http;
using wavebench::testing::RawReply;

class HostileHttp : public DaemonFixture {
 protected:
  unsigned short port() const { return daemon_->port(); }
  std::string host() const { return "127.0.0.1:" + std::to_string(port()); }

  // An error answer the daemon meant: a 4xx status with {"error", "detail"}.
  static ::testing::AssertionResult is_client_error(const RawReply& r) {
    if (!r.answered) return ::testing::AssertionFailure() << "no HTTP answer";
    if (r.status < 400 || r.status > 499) {
      return ::testing::AssertionFailure() << "status " << r.status << ": " << r.body;
    }
    if (r.json.is_discarded() || !r.json.is_object() || !r.json.contains("error") ||
        !r.json.contains("detail")) {
      return ::testing::AssertionFailure() << "not the API's error JSON: " << r.body;
    }
    return ::testing::AssertionSuccess();
  }

  void expect_daemon_alive_and_untouched() {
    const auto status = raw_http(port(), get_request("/api/status", host()));
    ASSERT_TRUE(status.answered);
    EXPECT_EQ(status.status, 200);
    EXPECT_EQ(status.json.value("state", ""), "ready") << status.body;
    EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);
    EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());
  }
};

std::string hex_escape(int byte) {
  char text[4];
  std::snprintf(text, sizeof text, "%%%02X", byte);
  return text;
}

TEST_F(HostileHttp, BytesThatAreNotUtf8InTheTargetGetAnAnswerNotACrash) {
  // The forms of the probe that killed the daemon, then every non-ASCII and control byte in
  // each place a target carries text.
  std::vector<std::string> targets = {"/api/runs/%ff",
                                      "/api/%ff",
                                      "/api/runs?limit=%ff",
                                      "/api/live?since=%ff",
                                      "/api/runs?unit=%ff%fe",
                                      "/api/runs?status=%c3%28",
                                      "/api/runs?%ff=1",
                                      "/api/runs/%ff/samples",
                                      "/api/runs/20260101T000000.000000Z/samples?from=%ff",
                                      "/%ff",
                                      "/api/status%ff",
                                      "/api/runs?procedure=%ed%a0%80",
                                      "/api/runs/%f4%90%80%80"};
  const std::vector<std::string> places = {
      "/api/runs/X",      "/api/X",        "/api/runs?limit=X",  "/api/live?since=X",
      "/api/runs?unit=X", "/api/runs?X=1", "/api/runs/X/samples"};
  for (const auto& place : places) {
    for (int byte = 1; byte < 256; ++byte) {
      if (byte >= 0x20 && byte < 0x7F) continue;
      auto target = place;
      target.replace(target.find('X'), 1, hex_escape(byte));
      targets.push_back(target);
    }
  }
  int answered = 0;
  for (const auto& target : targets) {
    for (const char* method : {"GET", "POST"}) {
      const auto r =
          raw_http(port(), std::string(method) + " " + target + " HTTP/1.1\r\nHost: " + host() +
                               "\r\nContent-Length: 0\r\nConnection: "
                               "close\r\n\r\n");
      EXPECT_TRUE(is_client_error(r)) << method << " " << target;
      answered += is_client_error(r) ? 1 : 0;
    }
  }
  // Raw bytes, not %-escaped.
  for (int byte = 0x80; byte < 256; ++byte) {
    const auto r = raw_http(
        port(), get_request("/api/runs/" + std::string(1, static_cast<char>(byte)), host()));
    EXPECT_TRUE(is_client_error(r)) << "raw byte " << byte;
    answered += is_client_error(r) ? 1 : 0;
  }
  std::printf("[ hostile  ] %d requests with bad bytes in the target, %d answered 4xx with JSON\n",
              static_cast<int>(2 * targets.size() + 128), answered);
  expect_daemon_alive_and_untouched();
}

TEST_F(HostileHttp, DeepLongOrBrokenJsonBodiesAreRefusedWith400) {
  const std::string deep_array(100000, '[');
  std::string deep_object;
  for (int i = 0; i < 20000; ++i) deep_object += "{\"a\":";
  std::string many_numbers = "[";
  for (int i = 0; i < 20000; ++i) many_numbers += (i ? ",0" : "0");
  many_numbers += "]";
  const std::vector<std::string> bodies = {
      R"({"procedure":"static","twin":)" + deep_array,
      R"({"procedure":"static","options":)" + deep_object,
      deep_array,
      R"({"procedure":"static","options":{"loads_nm":)" + many_numbers + "}}",
      "{\"procedure\":\"st\xff\xfe\"}",
      "{\"procedure\":\"static\",\"options\":{\"x\":\"\xc3\x28\"}}",
      R"({"procedure":"static","options":{"a":)" + std::string(17, '[') + std::string(17, ']') +
          "}}",
      "",
      "null",
      "[]",
      R"("static")",
      R"({"procedure":"static"} trailing)",
      R"({"procedure":"static","options":{"seconds":-1}})",
      R"({"procedure":"static","options":[]})",
      R"({"procedure":42})",
      R"({"procedure":"nope"})",
      R"({"procedure":"static","twin":"yes"})",
      R"({"procedure":"static","extra":1})",
  };
  int refused = 0;
  for (const auto& body : bodies) {
    const auto r = raw_http(port(), post_request("/api/runs", host(), body, kToken));
    EXPECT_TRUE(is_client_error(r)) << body.substr(0, 80);
    EXPECT_EQ(r.status, 400) << body.substr(0, 80) << " -> " << r.body.substr(0, 300);
    refused += r.status == 400 ? 1 : 0;
  }
  // Over the body limit: 413 before the body is read whole.
  const auto big =
      raw_http(port(), post_request("/api/runs", host(), std::string(2u << 20, ' '), kToken));
  EXPECT_TRUE(is_client_error(big));
  EXPECT_EQ(big.status, 413);
  std::printf("[ hostile  ] %zu malformed start bodies, %d refused with 400; 1 oversized, %d\n",
              bodies.size(), refused, big.status);
  expect_daemon_alive_and_untouched();
}

TEST_F(HostileHttp, AForeignHostHeaderIsRefusedBeforeAnythingElse) {
  const std::vector<std::string> foreign = {"evil.example",
                                            "evil.example:" + std::to_string(port()),
                                            "127.0.0.1.evil.example",
                                            "localhost.evil.example",
                                            "attacker.com:80",
                                            "[::1",
                                            "127.0.0.1:99999",
                                            "%31%32%37.0.0.1",
                                            "[fe80::1%25eth0]:8470",
                                            "LOCALHOST.",
                                            ""};
  int refused = 0;
  int tried = 0;
  for (const auto& h : foreign) {
    for (const char* target : {"/api/status", "/api/runs", "/api/live", "/api/runs/x/samples"}) {
      const auto r = raw_http(port(), get_request(target, h));
      ++tried;
      EXPECT_TRUE(is_client_error(r)) << h << " " << target;
      refused += is_client_error(r) ? 1 : 0;
    }
    const auto start =
        raw_http(port(), post_request("/api/runs", h, R"({"procedure":"static"})", kToken));
    const auto stop = raw_http(port(), post_request("/api/stop", h, "{}", kToken));
    tried += 2;
    EXPECT_TRUE(is_client_error(start)) << h;
    EXPECT_TRUE(is_client_error(stop)) << h;
    refused += (is_client_error(start) ? 1 : 0) + (is_client_error(stop) ? 1 : 0);
  }
  // Two Host headers: which one counts would depend on who reads them.
  const auto two = raw_http(port(), "GET /api/status HTTP/1.1\r\nHost: " + host() +
                                        "\r\nHost: evil.example\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(is_client_error(two));
  // No Host at all.
  const auto none = raw_http(port(), "GET /api/status HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(is_client_error(none));
  std::printf(
      "[ hostile  ] %d requests with a foreign Host, %d refused; duplicate Host %d, no "
      "Host %d\n",
      tried, refused, two.status, none.status);
  // The daemon's own names still work.
  for (const auto& own : {host(), "localhost:" + std::to_string(port()),
                          "[::1]:" + std::to_string(port()), std::string("127.0.0.1")}) {
    EXPECT_EQ(raw_http(port(), get_request("/api/status", own)).status, 200) << own;
  }
  expect_daemon_alive_and_untouched();
}

TEST_F(HostileHttp, BrokenOrOversizedHeadersGetAnHttpErrorNotAReset) {
  const std::vector<std::pair<std::string, int>> requests = {
      {get_request("/api/status", host(), "X-Big: " + std::string(20000, 'a') + "\r\n"), 431},
      {get_request("/api/status", host(),
                   [] {
                     std::string many;
                     for (int i = 0; i < 40; ++i)
                       many += "X-" + std::to_string(i) + ": " + std::string(500, 'b') + "\r\n";
                     return many;
                   }()),
       431},
      {get_request("/api/status", host(), std::string("X-Nul: a\0b\r\n", 12)), 400},
      {get_request("/api/status", host(),
                   "X-Ctl: a\x01"
                   "b\r\n"),
       400},
      {get_request("/api/status", host(), "Bad Header Name: x\r\n"), 400},
      {"GARBAGE\r\n\r\n", 400},
      {"GET /api/status HTTP/9.9\r\nHost: " + host() + "\r\n\r\n", 400},
      {"GET /api/status HTTP/1.1\r\nHost: " + host() + "\r\nContent-Length: -5\r\n\r\n", 400},
      {"GET /api/status HTTP/1.1\r\nHost: " + host() +
           "\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n",
       400},
      {"GET " + std::string(20000, '/') + " HTTP/1.1\r\nHost: " + host() + "\r\n\r\n", 431},
  };
  int answered = 0;
  for (const auto& [bytes, expected] : requests) {
    const auto r = raw_http(port(), bytes);
    EXPECT_TRUE(is_client_error(r)) << bytes.substr(0, 60);
    EXPECT_EQ(r.status, expected) << bytes.substr(0, 60) << " -> " << r.body;
    answered += r.answered ? 1 : 0;
  }
  std::printf("[ hostile  ] %zu broken or oversized requests, %d answered with an HTTP error\n",
              requests.size(), answered);
  expect_daemon_alive_and_untouched();
}

TEST_F(HostileHttp, RunIdsThatAreNotRunIdsNeverReachTheFileSystem) {
  const std::vector<std::string> ids = {"..",
                                        "%2e%2e",
                                        "%2e%2e%2f%2e%2e%2fetc%2fpasswd",
                                        "..%2findex.sqlite",
                                        "index.sqlite",
                                        "logs",
                                        "%2fetc%2fpasswd",
                                        "20261122T045843.123456Z%2f..",
                                        "20261122T045843.123456",
                                        std::string(300, 'a')};
  int not_found = 0;
  for (const auto& id : ids) {
    for (const auto& suffix : {std::string(), std::string("/samples")}) {
      const auto r = raw_http(port(), get_request("/api/runs/" + id + suffix, host()));
      EXPECT_EQ(r.status, 404) << id << suffix << " -> " << r.body;
      not_found += r.status == 404 ? 1 : 0;
    }
  }
  std::printf("[ hostile  ] %zu path-traversal run ids, %d answered 404\n", 2 * ids.size(),
              not_found);
  expect_daemon_alive_and_untouched();
}

TEST_F(HostileHttp, AMalformedStartIs400EvenWhileARunIsActive) {
  const auto id = start_endless_run();
  const std::vector<std::string> bodies = {R"({})",
                                           R"({"procedure":"nope"})",
                                           R"({"procedure":"static","options":{"seconds":-1}})",
                                           R"({"procedure":"static","options":"x"})",
                                           R"({"procedure":"static","report":1})",
                                           std::string(40, '[')};
  for (const auto& body : bodies) {
    const auto r = raw_http(port(), post_request("/api/runs", host(), body, kToken));
    EXPECT_EQ(r.status, 400) << body << " -> " << r.body;
  }
  // A well-formed one is refused for being second, and says so.
  const auto second =
      raw_http(port(), post_request("/api/runs", host(), R"({"procedure":"static"})", kToken));
  EXPECT_EQ(second.status, 409) << second.body;
  std::printf("[ hostile  ] %zu malformed starts during a run: 400 each; a valid one: %d\n",
              bodies.size(), second.status);
  ASSERT_EQ(client().post("/api/abort").status, 200);
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
  const auto runs = client().get("/api/runs").body["runs"];
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["id"], id);
}

TEST(HostileHttpText, AnAnswerHoldingBytesThatAreNotUtf8StillSerialises) {
  // A unit serial or a path that slipped through with bad bytes must not take the daemon down
  // when the answer is written (the probe's crash: json::dump threw type_error 316).
  ApiResponse r{200, {{"unit_serial", std::string("SN-\xff\xfe-1")}, {"ok", true}}};
  const auto text = response_text(r);
  const auto back = nlohmann::json::parse(text, nullptr, false);
  ASSERT_FALSE(back.is_discarded()) << text;
  EXPECT_EQ(back["unit_serial"], "SN-\xef\xbf\xbd\xef\xbf\xbd-1");  // U+FFFD twice
  const auto error = api_error(404, "not found", std::string("no resource at /api/\xff\x01"));
  EXPECT_EQ(error.body["detail"], "no resource at /api/\\xff\\x01");
}

TEST(HostileHttpDeathTest, TheLastResortGuardRunsItsActionBeforeTheProcessEnds) {
  const auto marker = fresh_test_dir() / "guard-ran";
  EXPECT_DEATH(
      {
        install_last_resort_guard([&](const std::string& what) {
          std::ofstream(marker) << what;  // stands in for: bench safe, run marked
        });
        std::thread([] { throw std::runtime_error("escaped from an API thread"); }).join();
      },
      "");
  std::ifstream in(marker);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "uncaught exception: escaped from an API thread");
}

}  // namespace
}  // namespace wavebench::daemon::testing
