// Operators by name (issue #21): the accounts file (bad files refused naming the key), Argon2id
// passwords, the login rate limit, session timeouts, the operator's role and name in the run,
// and the operator's stop, which is not a fault.
#include "wavebench/daemon/accounts.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>

#include "daemon_fixture.hpp"
#include "wavebench/daemon/browser_request.hpp"
#include "wavebench/daemon/login_throttle.hpp"
#include "wavebench/daemon/session_table.hpp"

namespace wavebench::daemon::testing {
namespace {

// One hash for the whole file: Argon2id costs ~0.1 s and 64 MiB by design.
const std::string& anna_hash() {
  static const std::string hash = hash_password("correct horse");
  return hash;
}

std::string file_with(const std::string& entry) {
  return "accounts:\n" + entry;
}

TEST(AccountsFile, AGoodFileLoads) {
  const auto accounts =
      parse_accounts(file_with("  - {name: anna, password_hash: \"" + anna_hash() +
                               "\", role: operator}\n"
                               "  - {name: ed.x-1, password_hash: \"" +
                               anna_hash() + "\", role: engineer}\n"),
                     "test");
  ASSERT_EQ(accounts.size(), 2u);
  EXPECT_EQ(accounts.find("anna")->role, Role::kOperator);
  EXPECT_EQ(accounts.find("ed.x-1")->role, Role::kEngineer);
  EXPECT_EQ(accounts.find("nobody"), nullptr);
  // What `wavebench account add` writes reads back the same.
  const auto again = parse_accounts(accounts_yaml(accounts), "again");
  EXPECT_EQ(again.find("ed.x-1")->password_hash, anna_hash());
}

TEST(AccountsFile, BadFilesAreRefusedNamingKeyValueAndExpectation) {
  const std::string h = "\"" + anna_hash() + "\"";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"accounts: 3\n", {"accounts", "a list"}},
      {"users: []\n", {"users", "only 'accounts'"}},
      {"- a\n", {"(file)", "a map"}},
      {"accounts: [: :\n", {"(file)", "YAML"}},
      {file_with("  - {name: anna, password_hash: " + h + ", role: admin}\n"),
       {"accounts[0].role", "'admin'", "operator or engineer"}},
      {file_with("  - {name: \"an na\", password_hash: " + h + ", role: operator}\n"),
       {"accounts[0].name", "'an na'", "A-Z a-z 0-9"}},
      {file_with("  - {name: " + std::string(65, 'a') + ", password_hash: " + h +
                 ", role: operator}\n"),
       {"accounts[0].name", "1 to 64"}},
      {file_with("  - {name: anna, password_hash: plaintext, role: operator}\n"),
       {"accounts[0].password_hash", "'plaintext'", "Argon2id"}},
      {file_with("  - {name: anna, password_hash: \"$argon2i$v=19$m=4096\", role: operator}\n"),
       {"accounts[0].password_hash", "Argon2id"}},
      {file_with("  - {name: anna, role: operator}\n"), {"accounts[0].password_hash", "a string"}},
      {file_with("  - {name: anna, password_hash: " + h + ", role: operator, admin: true}\n"),
       {"accounts[0].admin", "name, password_hash or role"}},
      {file_with("  - {name: anna, password_hash: " + h +
                 ", role: operator}\n"
                 "  - {name: anna, password_hash: " +
                 h + ", role: engineer}\n"),
       {"accounts[1].name", "'anna'", "not used before"}},
      {std::string(kMaxAccountsFileBytes + 1, '#'), {"(file)", "at most"}},
  };
  for (const auto& [text, wanted] : cases) {
    try {
      (void)parse_accounts(text, "accounts.yaml");
      ADD_FAILURE() << "accepted: " << text.substr(0, 200);
    } catch (const AccountsFileRefused& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("accounts.yaml"), std::string::npos) << what;
      for (const auto& w : wanted)
        EXPECT_NE(what.find(w), std::string::npos) << w << " in " << what;
    }
  }
  std::string many = "accounts:\n";
  for (std::size_t i = 0; i <= kMaxAccounts; ++i) many += "  - {}\n";
  EXPECT_THROW((void)parse_accounts(many, "many"), AccountsFileRefused);
  EXPECT_THROW((void)load_accounts("/nonexistent/accounts.yaml"), AccountsFileRefused);
}

TEST(Passwords, Argon2idVerifies) {
  EXPECT_EQ(anna_hash().rfind("$argon2id$", 0), 0u);
  EXPECT_TRUE(verify_password(anna_hash(), "correct horse"));
  EXPECT_FALSE(verify_password(anna_hash(), "correct horsE"));
  EXPECT_FALSE(verify_password(anna_hash(), ""));
  EXPECT_FALSE(verify_password(anna_hash(), std::string(kMaxPasswordLength + 1, 'x')));
  EXPECT_FALSE(verify_password("garbage", "correct horse"));
  EXPECT_NE(hash_password("correct horse"), anna_hash());  // salted
  EXPECT_THROW((void)hash_password(""), std::invalid_argument);
}

TEST(LoginThrottle, TenWrongPasswordsInARowAreSlowedDown) {
  auto now = std::chrono::steady_clock::time_point{};
  LoginThrottle throttle([&] { return now; });
  int refused = 0;
  std::chrono::seconds waited{0};
  for (int attempt = 0; attempt < 10; ++attempt) {
    const auto wait = throttle.wait("name:anna");
    if (wait.count() > 0) {
      ++refused;
      waited += wait;
      now += wait;  // a patient guesser waits, then fails again
    }
    throttle.failed("name:anna");
  }
  // Five free failures, then 1 + 2 + 4 + 8 + 16 s of waiting.
  EXPECT_EQ(refused, 5);
  EXPECT_EQ(waited.count(), 31);
  EXPECT_EQ(throttle.wait("name:anna").count(), 32);
  EXPECT_EQ(throttle.wait("name:ed").count(), 0);  // another name is not held up
  throttle.succeeded("name:anna");
  EXPECT_EQ(throttle.wait("name:anna").count(), 0);
}

TEST(SessionTable, IdleTimeoutAndAbsoluteCap) {
  auto now = std::chrono::steady_clock::time_point{};
  SessionTable table(
      8, std::chrono::seconds(30), [&] { return now; }, std::chrono::seconds(100));
  const auto id = table.create({"anna", Role::kOperator});
  now += std::chrono::seconds(29);
  ASSERT_TRUE(table.use(id));
  EXPECT_EQ(table.use(id)->account, "anna");
  now += std::chrono::seconds(30);  // idle too long
  EXPECT_FALSE(table.use(id));
  const auto busy = table.create();
  for (int i = 0; i < 3; ++i) {  // used every 25 s, up to 75 s old
    now += std::chrono::seconds(25);
    EXPECT_TRUE(table.use(busy)) << i;  // kept alive by use...
  }
  now += std::chrono::seconds(25);
  EXPECT_FALSE(table.use(busy));  // ...up to its absolute cap (100 s old now)
}

class AccountsApiTest : public DaemonFixture {
 protected:
  void SetUp() override {
    dir_ = fresh_test_dir();
    logins_.accounts =
        Accounts({{"anna", anna_hash(), Role::kOperator}, {"ed", anna_hash(), Role::kEngineer}});
    start_daemon();
  }
  ApiRequest request(std::string method, std::string target, std::string body = {}) const {
    ApiRequest r;
    r.method = std::move(method);
    r.target = std::move(target);
    r.host = "127.0.0.1:8470";
    r.body = std::move(body);
    r.console_request = "console";
    r.client = "127.0.0.1";
    return r;
  }
  ApiResponse handle(const ApiRequest& r) const { return daemon_->api().handle(r); }
  std::string login(const std::string& name, const std::string& password = "correct horse") {
    const auto answer = handle(request(
        "POST", "/api/session", nlohmann::json{{"name", name}, {"password", password}}.dump()));
    EXPECT_EQ(answer.status, 200) << response_text(answer);
    for (const auto& [key, value] : answer.headers) {
      if (key == "Set-Cookie")
        return cookie_value(value.substr(0, value.find(';')), "wb_session_8470");
    }
    return {};
  }
  ApiRequest as(const std::string& session, ApiRequest r) const {
    r.cookie = "wb_session_8470=" + session;
    return r;
  }
};

TEST_F(AccountsApiTest, AnOperatorCannotChangeASpecAndTheRunNamesThem) {
  const auto anna = login("anna");
  EXPECT_EQ(handle(as(anna, request("GET", "/api/session"))).body["account"], "anna");
  const auto refused = handle(as(anna, request("POST", "/api/runs",
                                               R"({"procedure": "static", "options":
                                                   {"limits": {"static.stiffness_nm_per_arcmin":
                                                   {"min": 1}}}})")));
  EXPECT_EQ(refused.status, 403) << response_text(refused);
  EXPECT_NE(refused.body["detail"].get<std::string>().find("role operator"), std::string::npos);
  EXPECT_EQ(handle(as(anna, request("POST", "/api/reset"))).status, 403);
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());  // nothing was started

  // Her start with the shipped limits goes ahead.
  const auto started = handle(as(anna, request("POST", "/api/runs",
                                               R"({"procedure": "dynamic",
                                                   "options": {"seconds": 1e6}})")));
  ASSERT_EQ(started.status, 201) << response_text(started);
  const auto id = started.body["run_id"].get<std::string>();
  // The console's stop, without any session: the run ends aborted, and the bench is ready.
  auto stop = request("POST", "/api/stop");
  stop.origin = "http://127.0.0.1:8470";
  stop.has_origin = true;
  ASSERT_EQ(handle(stop).status, 200);
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
  ASSERT_TRUE(eventually([&] { return client().get("/api/status").body["state"] == "ready"; }));
  const auto detail = client().get("/api/runs/" + id);
  EXPECT_EQ(detail.body["run"]["status"], "aborted");
  EXPECT_EQ(detail.body["run"]["reason"], "stopped by operator");
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);
  // The next start needs no reset; the run is in her name whatever the form said.
  const auto next = handle(
      as(anna, request("POST", "/api/runs", R"({"procedure": "static", "operator": "bob"})")));
  ASSERT_EQ(next.status, 201) << response_text(next);
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
  EXPECT_EQ(client()
                .get("/api/runs/" + next.body["run_id"].get<std::string>())
                .body["results"]["operator"],
            "anna");

  // An engineer may change the limits.
  const auto ed = login("ed");
  const auto engineer = handle(as(ed, request("POST", "/api/runs",
                                              R"({"procedure": "static", "options":
                                                  {"limits": {}}})")));
  EXPECT_NE(engineer.status, 403) << response_text(engineer);
}

TEST_F(AccountsApiTest, TheStopFromAnotherSiteOrWithoutTheHeaderIsRefused) {
  auto foreign = request("POST", "/api/stop");
  foreign.has_origin = true;
  foreign.origin = "http://evil.example";
  EXPECT_EQ(handle(foreign).status, 403);
  auto form = request("POST", "/api/stop");
  form.console_request.clear();
  EXPECT_EQ(handle(form).status, 401);
  auto start = request("POST", "/api/runs", R"({"procedure": "static"})");
  EXPECT_EQ(handle(start).status, 401);  // the header alone starts nothing
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);
}

TEST_F(AccountsApiTest, TenWrongPasswordsInARowAreRefusedWithRetryAfter) {
  std::vector<int> statuses;
  std::string retry_after;
  const auto started = std::chrono::steady_clock::now();
  for (int i = 0; i < 10; ++i) {
    const auto answer =
        handle(request("POST", "/api/session", R"({"name": "anna", "password": "wrong"})"));
    statuses.push_back(answer.status);
    for (const auto& [key, value] : answer.headers) {
      if (key == "Retry-After") retry_after = value;
      EXPECT_NE(key, "Set-Cookie");
    }
  }
  const auto took = std::chrono::duration<double>(std::chrono::steady_clock::now() - started);
  std::printf("10 wrong passwords: statuses");
  for (const auto s : statuses) std::printf(" %d", s);
  std::printf(", %.2f s, Retry-After %s\n", took.count(), retry_after.c_str());
  EXPECT_EQ(std::count(statuses.begin(), statuses.end(), 401), 5);
  EXPECT_EQ(std::count(statuses.begin(), statuses.end(), 429), 5);
  EXPECT_FALSE(retry_after.empty());
  // Even the right password waits now: the guesser cannot tell when they hit it.
  const auto right =
      handle(request("POST", "/api/session", R"({"name": "anna", "password": "correct horse"})"));
  EXPECT_EQ(right.status, 429);
  // An unknown name is refused like a wrong password.
  auto other = request("POST", "/api/session", R"({"name": "nobody", "password": "x"})");
  other.client = "10.0.0.2";
  EXPECT_EQ(handle(other).status, 401);
}

TEST_F(AccountsApiTest, SessionsTimeOutWhenIdle) {
  daemon_.reset();
  logins_.idle_timeout = std::chrono::seconds(1);
  logins_.max_age = std::chrono::seconds(1);
  start_daemon();
  const auto anna = login("anna");
  EXPECT_EQ(handle(as(anna, request("GET", "/api/session"))).body["authenticated"], true);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  EXPECT_EQ(handle(as(anna, request("GET", "/api/session"))).body["authenticated"], false);
  EXPECT_EQ(handle(as(anna, request("POST", "/api/runs", R"({"procedure": "static"})"))).status,
            401);
}

}  // namespace
}  // namespace wavebench::daemon::testing
