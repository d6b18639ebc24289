// A lone bench without `--results`: wavebenchd fills its own store (index.sqlite) at the end of
// each run, /api/status says so, /api/fleet and `wavebench fleet --runs DIR` answer from it with
// the figures of the runs' own results.json.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <csignal>
#include <fstream>

#include "cli_run.hpp"
#include "daemon_process.hpp"
#include "daemon_runs.hpp"
#include "synthetic_runs.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/http_target.hpp"

namespace wavebench::fleet {
namespace {

using daemon::DaemonClient;
using daemon::testing::DaemonProcess;
using testing::eventually;

constexpr const char* kToken = "fedcba9876543210fedcba9876543210";

class OwnStoreDaemon : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    token_ = dir_ / "token";
    std::ofstream(token_) << kToken << "\n";
    ::chmod(token_.c_str(), 0600);
  }
  std::unique_ptr<DaemonProcess> start_daemon() {
    auto p = std::make_unique<DaemonProcess>(
        std::vector<std::string>{WAVEBENCHD_PATH, "--config", "sim", "--runs", runs().string(),
                                 "--listen", "127.0.0.1:0", "--token-file", token_.string()},
        dir_ / "stderr.txt");
    port_ = p->wait_for_port();
    return p;
  }
  DaemonClient client() const { return {"http://127.0.0.1:" + std::to_string(port_), kToken}; }
  std::filesystem::path runs() const { return dir_ / "runs"; }
  // The largest static pass of a run's results.json.
  double largest_p2p(const std::string& id) const {
    std::ifstream in(runs() / id / "results.json");
    const auto results = nlohmann::json::parse(in);
    double largest = 0;
    for (const auto& pass : results["static"]) {
      largest = std::max(largest, pass["p2p_arcmin"].get<double>());
    }
    return largest;
  }

  std::filesystem::path dir_, token_;
  int port_ = 0;
};

TEST_F(OwnStoreDaemon, RunsReachTheBenchsOwnStoreAndItsQueries) {
  auto daemon = start_daemon();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  auto api = client();
  std::vector<std::string> ids;
  for (int i = 0; i < 2; ++i) ids.push_back(testing::run_to_the_end(api));
  ASSERT_FALSE(ids[0].empty() || ids[1].empty());

  nlohmann::json store;
  ASSERT_TRUE(eventually(
      [&] {
        store = api.get("/api/status").body.value("results_store", nlohmann::json());
        return store.is_object() && store["pending"] == 0 && store["sent"] == 2;
      },
      std::chrono::seconds(30)))
      << store.dump();
  EXPECT_EQ(store["kind"], "sqlite");
  EXPECT_TRUE(store["last_error"].is_null()) << store.dump();
  EXPECT_TRUE(store["last_published_at"].is_string()) << store.dump();
  EXPECT_TRUE(store["next_attempt_in_s"].is_null()) << store.dump();

  const std::string model = daemon::url_encode(testing::kSimModel);
  const auto listed = api.get("/api/fleet/runs?model=" + model);
  ASSERT_EQ(listed.status, 200) << listed.body.dump();
  ASSERT_EQ(listed.body["runs"].size(), 2u);
  EXPECT_EQ(listed.body["runs"][0]["run_id"], ids[1]);  // newest first
  EXPECT_EQ(listed.body["runs"][0]["bench"], "sim");    // the bench config's name
  EXPECT_DOUBLE_EQ(listed.body["runs"][0]["figures"]["static_te_p2p"].get<double>(),
                   largest_p2p(ids[1]));

  const auto spc = api.get("/api/fleet/spc?figure=static_te_p2p&model=" + model);
  ASSERT_EQ(spc.status, 200) << spc.body.dump();
  ASSERT_EQ(spc.body["points"].size(), 2u);
  EXPECT_EQ(spc.body["points"][0]["run_id"], ids[0]);                // oldest first
  EXPECT_DOUBLE_EQ(spc.body["limits"]["upper"].get<double>(), 7.0);  // sim-seed004's limit
  EXPECT_EQ(spc.body["spc"]["n"], 2);
  const double mean = (largest_p2p(ids[0]) + largest_p2p(ids[1])) / 2;
  EXPECT_NEAR(spc.body["spc"]["mean"].get<double>(), mean, 1e-12);
  const auto bad = api.get("/api/fleet/trend?figure=nonsense&model=x");
  EXPECT_EQ(bad.status, 400) << bad.body.dump();

  // The CLI reads the same store straight from the folder, the daemon still running.
  const auto cli = wavebench::testing::run_cli("fleet spc --runs '" + runs().string() +
                                                   "' --figure static_te_p2p --model '" +
                                                   testing::kSimModel + "' --json",
                                               dir_ / "cli.txt");
  ASSERT_EQ(cli.exit_code, 0) << cli.output;
  const auto answer = nlohmann::json::parse(cli.output);
  EXPECT_EQ(answer["spc"]["n"], 2);
  EXPECT_DOUBLE_EQ(answer["spc"]["mean"].get<double>(), spc.body["spc"]["mean"].get<double>());

  // Started again, the daemon summarises nothing twice.
  daemon->signal(SIGTERM);
  daemon->wait();
  daemon = start_daemon();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  EXPECT_TRUE(
      eventually([&] { return daemon->stderr_text().find("0 runs to send") != std::string::npos; },
                 std::chrono::seconds(10)))
      << daemon->stderr_text();
  const auto again = client().get("/api/fleet/runs");
  ASSERT_EQ(again.status, 200) << again.body.dump();
  EXPECT_EQ(again.body["runs"].size(), 2u);
}

// `wavebench run` without a daemon summarises its run into the folder's store itself; a daemon
// started on the folder afterwards finds it there and adds nothing.
TEST_F(OwnStoreDaemon, ACliRunReachesTheStoreWithoutADaemonAndOnlyOnce) {
  const auto run = wavebench::testing::run_cli(
      "run static --bench sim --out '" + runs().string() +
          "' --positions 4 --loads 0 --window 0.05 --spec sim-seed004 --no-report --quiet",
      dir_ / "run.txt");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("not summarised"), std::string::npos) << run.output;
  const auto listed = wavebench::testing::run_cli("fleet spc --runs '" + runs().string() +
                                                      "' --figure static_te_p2p --model '" +
                                                      testing::kSimModel + "' --json",
                                                  dir_ / "spc.txt");
  ASSERT_EQ(listed.exit_code, 0) << listed.output;
  const auto answer = nlohmann::json::parse(listed.output);
  ASSERT_EQ(answer["points"].size(), 1u) << listed.output;
  const std::string id = answer["points"][0]["run_id"];
  EXPECT_DOUBLE_EQ(answer["points"][0]["value"].get<double>(), largest_p2p(id));

  auto daemon = start_daemon();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  auto api = client();
  nlohmann::json store;
  ASSERT_TRUE(eventually(
      [&] {
        store = api.get("/api/status").body.value("results_store", nlohmann::json());
        return store.is_object() && store["pending"] == 0;
      },
      std::chrono::seconds(30)))
      << store.dump();
  const auto again = api.get("/api/fleet/runs");
  ASSERT_EQ(again.status, 200) << again.body.dump();
  ASSERT_EQ(again.body["runs"].size(), 1u) << again.body.dump();
  EXPECT_EQ(again.body["runs"][0]["run_id"], id);
}

// `wavebench run --out` on the folder a live daemon writes is refused naming the daemon, before
// the bench moves; the daemon's runs are untouched.
TEST_F(OwnStoreDaemon, ACliRunIntoALiveDaemonsFolderIsRefused) {
  auto daemon = start_daemon();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  const auto run =
      wavebench::testing::run_cli("run static --bench sim --out '" + runs().string() +
                                      "' --positions 4 --loads 0 --window 0.05 --no-report --quiet",
                                  dir_ / "run.txt");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("in use by process"), std::string::npos) << run.output;
  const auto listed = client().get("/api/runs");
  ASSERT_EQ(listed.status, 200) << listed.body.dump();
  EXPECT_EQ(listed.body["total"], 0) << listed.body.dump();
}

TEST_F(OwnStoreDaemon, CliRefusesAFolderWithoutAStore) {
  std::filesystem::create_directories(runs());
  const auto none =
      wavebench::testing::run_cli("fleet runs --runs '" + runs().string() + "'", dir_ / "none.txt");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("--runs"), std::string::npos) << none.output;
  {
    storage::RunStore local(runs(), "test");  // an index, never summarised by a daemon
    testing::add_synthetic_run(local, {});
  }
  const auto empty = wavebench::testing::run_cli("fleet runs --runs '" + runs().string() + "'",
                                                 dir_ / "empty.txt");
  EXPECT_EQ(empty.exit_code, 1) << empty.output;
  EXPECT_NE(empty.output.find("no run summaries"), std::string::npos) << empty.output;
}

}  // namespace
}  // namespace wavebench::fleet
