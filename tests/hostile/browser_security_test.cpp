// The console's browser security at the DaemonApi level (issue #10): a session cookie is made
// only from the token; a change needs the token, or a live session plus the console's header;
// a foreign Origin or Host is refused; the session table stays bounded. Every refused attempt
// is counted and nothing moves.
#include <gtest/gtest.h>

#include <chrono>

#include "daemon_fixture.hpp"
#include "wavebench/daemon/browser_request.hpp"
#include "wavebench/daemon/session_table.hpp"

namespace wavebench::daemon::testing {
namespace {

class BrowserSecurityTest : public DaemonFixture {
 protected:
  ApiRequest request(std::string method, std::string target, std::string body = {}) const {
    ApiRequest r;
    r.method = std::move(method);
    r.target = std::move(target);
    r.host = "127.0.0.1:8470";
    r.body = std::move(body);
    r.console_request = "console";
    r.has_origin = true;
    r.origin = "http://127.0.0.1:8470";
    return r;
  }
  ApiResponse handle(const ApiRequest& r) const { return daemon_->api().handle(r); }

  // Logs in and returns the session id from Set-Cookie.
  std::string login() const {
    const auto answer =
        handle(request("POST", "/api/session", R"({"token": ")" + std::string(kToken) + "\"}"));
    EXPECT_EQ(answer.status, 200) << response_text(answer);
    for (const auto& [name, value] : answer.headers) {
      if (name == "Set-Cookie") {
        EXPECT_NE(value.find("HttpOnly"), std::string::npos);
        EXPECT_NE(value.find("SameSite=Strict"), std::string::npos);
        EXPECT_NE(value.find("Path=/"), std::string::npos);
        EXPECT_NE(value.find("Max-Age=1800"), std::string::npos);  // the idle timeout
        return cookie_value(value.substr(0, value.find(';')), "wb_session_8470");
      }
    }
    ADD_FAILURE() << "no Set-Cookie";
    return {};
  }
  ApiRequest stop_with(const std::string& session) const {
    auto r = request("POST", "/api/stop");
    r.cookie = "other=1; wb_session_8470=" + session;
    return r;
  }
  // A start: unlike the stop (issue #21: needs no session), it needs a live one.
  ApiRequest start_with(const std::string& session) const {
    auto r = stop_with(session);
    r.target = "/api/runs";
    r.body = R"({"procedure": "static"})";
    return r;
  }
};

TEST_F(BrowserSecurityTest, LoginNeedsTheTokenAndGivesA256BitHttpOnlyCookie) {
  int refused = 0;
  for (const auto* body : {R"({"token": "wrong-token-0123456789"})", R"({"token": ""})", "{}",
                           R"({"token": 12})", "not json", R"(["token"])"}) {
    const auto answer = handle(request("POST", "/api/session", body));
    EXPECT_GE(answer.status, 400) << body;
    EXPECT_LT(answer.status, 500) << body;
    for (const auto& [name, value] : answer.headers) EXPECT_NE(name, "Set-Cookie") << body;
    ++refused;
  }
  EXPECT_EQ(refused, 6);
  EXPECT_EQ(handle(request("POST", "/api/session", std::string(5000, ' '))).status, 413);
  const auto id = login();
  EXPECT_EQ(id.size(), 64u);  // 256 bits in hex
  EXPECT_NE(id, login());     // each login its own session
  auto check = request("GET", "/api/session");
  EXPECT_EQ(handle(check).body["authenticated"], false);
  check.cookie = "wb_session_8470=" + id;
  EXPECT_EQ(handle(check).body["authenticated"], true);
}

TEST_F(BrowserSecurityTest, ASessionWithTheConsoleHeaderMayStopAndLogoutEndsIt) {
  const auto id = login();
  EXPECT_EQ(handle(stop_with(id)).status, 200);
  auto logout = request("DELETE", "/api/session");
  logout.cookie = "wb_session_8470=" + id;
  const auto out = handle(logout);
  EXPECT_EQ(out.status, 200);
  ASSERT_FALSE(out.headers.empty());
  EXPECT_NE(out.headers[0].second.find("Max-Age=0"), std::string::npos);
  EXPECT_EQ(handle(start_with(id)).status, 401);
  EXPECT_EQ(handle(stop_with(id)).status, 200);  // the stop needs no session
}

TEST_F(BrowserSecurityTest, ForgedSessionsMissingHeaderAndForeignOriginsAreRefused) {
  const auto id = login();
  std::vector<std::pair<std::string, ApiRequest>> attempts;
  auto forged = start_with(std::string(64, 'a'));
  attempts.emplace_back("forged cookie", forged);
  auto flipped = id;
  flipped[0] = flipped[0] == 'a' ? 'b' : 'a';
  attempts.emplace_back("one digit changed", start_with(flipped));
  attempts.emplace_back("short cookie", start_with(id.substr(0, 32)));
  auto no_header = start_with(id);
  no_header.console_request.clear();
  attempts.emplace_back("header missing", no_header);
  auto foreign = start_with(id);
  foreign.origin = "http://127.0.0.1:8000";
  attempts.emplace_back("foreign origin (another port)", foreign);
  auto null_origin = start_with(id);
  null_origin.origin = "null";
  attempts.emplace_back("null origin", null_origin);
  auto bearer_foreign = request("POST", "/api/stop");
  bearer_foreign.authorization = std::string("Bearer ") + kToken;
  bearer_foreign.origin = "http://evil.example";
  attempts.emplace_back("token from a foreign origin", bearer_foreign);
  auto foreign_host = start_with(id);
  foreign_host.host = "evil.example:8470";
  foreign_host.origin = "http://evil.example:8470";
  attempts.emplace_back("foreign Host (DNS rebinding)", foreign_host);
  for (const auto* target : {"/api/runs", "/api/abort", "/api/reset", "/api/session"}) {
    auto preflight = stop_with(id);
    preflight.method = "OPTIONS";
    preflight.target = target;
    attempts.emplace_back(std::string("OPTIONS ") + target, preflight);
  }
  auto start = stop_with(std::string(64, '0'));
  start.target = "/api/runs";
  start.body = R"({"procedure": "static"})";
  attempts.emplace_back("start with a forged cookie", start);
  auto login_foreign =
      request("POST", "/api/session", R"({"token": ")" + std::string(kToken) + "\"}");
  login_foreign.origin = "http://localhost:9999";
  attempts.emplace_back("login from a foreign origin", login_foreign);
  auto login_form = request("POST", "/api/session", R"({"token": ")" + std::string(kToken) + "\"}");
  login_form.console_request.clear();
  attempts.emplace_back("login without the header (a form)", login_form);

  int refused = 0;
  for (const auto& [what, attempt] : attempts) {
    const auto answer = handle(attempt);
    EXPECT_GE(answer.status, 400) << what;
    EXPECT_LT(answer.status, 500) << what;
    for (const auto& [name, value] : answer.headers) {
      EXPECT_EQ(name.rfind("Access-Control-", 0), std::string::npos) << what;
      EXPECT_NE(name, "Set-Cookie") << what;
    }
    refused += answer.status >= 400 ? 1 : 0;
  }
  EXPECT_EQ(refused, static_cast<int>(attempts.size()));
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);  // nothing was tripped
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());   // nothing was started
  // The CLI's way is unchanged: the token, no Origin, no header.
  ApiRequest cli;
  cli.method = "POST";
  cli.target = "/api/stop";
  cli.host = "127.0.0.1:8470";
  cli.authorization = std::string("Bearer ") + kToken;
  EXPECT_EQ(handle(cli).status, 200);
}

TEST(SessionTable, BoundedLeastRecentlyUsedGoesFirstAndUnusedSessionsExpire) {
  auto now = std::chrono::steady_clock::time_point{};
  SessionTable table(3, std::chrono::seconds(100), [&] { return now; });
  const auto a = table.create();
  now += std::chrono::seconds(1);
  const auto b = table.create();
  now += std::chrono::seconds(1);
  const auto c = table.create();
  now += std::chrono::seconds(1);
  EXPECT_TRUE(table.use(a));  // a is now the most recent
  const auto d = table.create();
  EXPECT_EQ(table.size(), 3u);
  EXPECT_FALSE(table.use(b));  // the least recently used went
  EXPECT_TRUE(table.use(a));
  EXPECT_TRUE(table.use(c));
  EXPECT_TRUE(table.use(d));
  now += std::chrono::seconds(99);  // a renewed session lives on
  EXPECT_TRUE(table.use(a));
  now += std::chrono::seconds(100);
  EXPECT_FALSE(table.use(a));  // expired after its lifetime unused
  EXPECT_EQ(table.size(), 0u);
  for (int i = 0; i < 1000; ++i) table.create();
  EXPECT_EQ(table.size(), 3u);
}

TEST(BrowserRequest, CookieAndOriginParsing) {
  EXPECT_EQ(cookie_value("a=1; wb_session=abc ; b=2", "wb_session"), "abc");
  EXPECT_EQ(cookie_value("xwb_session=abc", "wb_session"), "");
  EXPECT_EQ(cookie_value("", "wb_session"), "");
  EXPECT_TRUE(same_origin("http://127.0.0.1:8470", "127.0.0.1:8470"));
  EXPECT_TRUE(same_origin("http://LOCALHOST:8470", "localhost:8470"));
  EXPECT_FALSE(same_origin("https://127.0.0.1:8470", "127.0.0.1:8470"));
  EXPECT_FALSE(same_origin("http://127.0.0.1:8471", "127.0.0.1:8470"));
  EXPECT_FALSE(same_origin("http://127.0.0.1:8470.evil", "127.0.0.1:8470"));
  EXPECT_FALSE(same_origin("null", "127.0.0.1:8470"));
}

}  // namespace
}  // namespace wavebench::daemon::testing
