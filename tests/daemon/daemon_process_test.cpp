// wavebenchd as its own process on the in-process simulated bench: killed with SIGKILL
// mid-run it leaves the run incomplete with its samples readable; SIGTERM ends the run aborted
// and exits 0; a bad config exits 2 before anything is created.
#include "daemon_process.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "test_dir.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {
namespace {

constexpr const char* kTokenText = "fedcba9876543210fedcba9876543210";

// A dynamic run with an hour of run-in (bench time): whatever the machine's speed, the run is
// still acquiring when the test acts on it.
const nlohmann::json kLongRun = {{"procedure", "dynamic"},
                                 {"options", {{"run_in_s", 3600}}},
                                 {"twin", false},
                                 {"report", false}};

class DaemonProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_test_dir();
    runs_ = dir_ / "runs";
    token_file_ = dir_ / "token";
    std::ofstream(token_file_) << kTokenText << "\n";
    std::filesystem::permissions(
        token_file_, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  }

  std::unique_ptr<DaemonProcess> start(const std::string& config = "sim") {
    auto p = std::make_unique<DaemonProcess>(
        std::vector<std::string>{WAVEBENCHD_PATH, "--config", config, "--runs", runs_.string(),
                                 "--listen", "127.0.0.1:0", "--token-file", token_file_.string()},
        dir_ / ("stderr." + std::to_string(++starts_) + ".txt"));
    port_ = p->wait_for_port();
    return p;
  }
  DaemonClient client() const { return {"http://127.0.0.1:" + std::to_string(port_), kTokenText}; }
  // Samples of `id` on disk as the daemon reports them.
  std::uint64_t samples_on_disk(const std::string& id) const {
    const auto reply = client().get("/api/runs/" + id + "/samples?limit=0");
    return reply.ok() ? reply.body.value("total", std::uint64_t{0}) : 0;
  }
  static bool eventually(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (std::chrono::steady_clock::now() < deadline) {
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return done();
  }

  std::filesystem::path dir_, runs_, token_file_;
  int port_ = 0;
  int starts_ = 0;
};

TEST_F(DaemonProcessTest, SigkillMidRunLeavesAnIncompleteRunWithItsSamplesReadable) {
  auto daemon = start();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  const auto started = client().post("/api/runs", kLongRun);
  ASSERT_EQ(started.status, 201) << started.body.dump();
  const auto id = started.body["run_id"].get<std::string>();
  std::uint64_t seen = 0;
  ASSERT_TRUE(eventually([&] { return (seen = samples_on_disk(id)) >= 500; }))
      << daemon->stderr_text();
  EXPECT_EQ(client().get("/api/status").body["state"], "running");

  daemon->signal(SIGKILL);
  const int status = daemon->wait();
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);

  auto restarted = start();
  ASSERT_GT(port_, 0) << restarted->stderr_text();
  const auto incomplete = client().get("/api/runs?status=incomplete").body["runs"];
  ASSERT_EQ(incomplete.size(), 1u);
  EXPECT_EQ(incomplete[0]["id"], id);
  EXPECT_EQ(client().get("/api/runs/" + id).body["run"]["status"], "incomplete");

  // Every sample the daemon had reported on disk before the kill is still there, intact.
  const auto log = storage::read_sample_log(runs_ / id / "samples.wbs");
  EXPECT_GE(log.samples.size(), seen);
  EXPECT_FALSE(log.corrupt_record);
  for (std::size_t i = 0; i < log.samples.size(); ++i) ASSERT_EQ(log.samples[i].index, i);
  const auto api = client().get("/api/runs/" + id + "/samples?from=0&limit=10");
  EXPECT_EQ(api.body["total"], log.samples.size());
  EXPECT_FALSE(api.body["corrupt"].get<bool>());
  ASSERT_EQ(api.body["samples"].size(), 10u);
  EXPECT_TRUE(api.body["samples"][9]["theta_in_rad"].is_number());

  // The restarted daemon is ready for the next run.
  EXPECT_EQ(client().get("/api/status").body["state"], "ready");
  restarted->signal(SIGTERM);
  EXPECT_EQ(restarted->wait(), 0);
}

TEST_F(DaemonProcessTest, SigtermEndsTheRunAbortedAndExitsZero) {
  auto daemon = start();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  const auto started = client().post("/api/runs", kLongRun);
  ASSERT_EQ(started.status, 201) << started.body.dump();
  const auto id = started.body["run_id"].get<std::string>();
  ASSERT_TRUE(eventually([&] { return samples_on_disk(id) >= 100; }));

  daemon->signal(SIGTERM);
  const int status = daemon->wait();
  ASSERT_TRUE(WIFEXITED(status)) << daemon->stderr_text();
  EXPECT_EQ(WEXITSTATUS(status), 0) << daemon->stderr_text();

  std::ifstream in(runs_ / id / "status.json");
  const auto run = nlohmann::json::parse(in);
  EXPECT_EQ(run["status"], "aborted");
  // The bench may prefix the kind of trip; the daemon's reason must be in it.
  EXPECT_NE(run["reason"].get<std::string>().find("daemon stopped by SIGTERM"), std::string::npos)
      << run.dump();
  EXPECT_GT(storage::read_sample_log(runs_ / id / "samples.wbs").samples.size(), 0u);
}

TEST_F(DaemonProcessTest, AbortTripsTheSimulatedBenchAndTheRunEndsAbortedUntilReset) {
  auto daemon = start();
  ASSERT_GT(port_, 0) << daemon->stderr_text();
  const auto started = client().post("/api/runs", kLongRun);
  ASSERT_EQ(started.status, 201) << started.body.dump();
  const auto id = started.body["run_id"].get<std::string>();
  ASSERT_TRUE(eventually([&] { return samples_on_disk(id) >= 100; }));

  ASSERT_EQ(client().post("/api/abort").status, 200);
  // The recording ends at once; the run is finished when its post-run work is (issue #21).
  ASSERT_TRUE(eventually([&] {
    const auto s = client().get("/api/status").body;
    return s["run"].is_null() && s["post_runs"].empty();
  }));
  const auto status = client().get("/api/status").body;
  EXPECT_EQ(status["state"], "fault");
  EXPECT_NE(status["fault_reason"].get<std::string>().find("operator abort"), std::string::npos);
  const auto run = client().get("/api/runs/" + id).body["run"];
  EXPECT_EQ(run["status"], "aborted");
  EXPECT_NE(run["reason"].get<std::string>().find("operator abort"), std::string::npos);
  EXPECT_GT(samples_on_disk(id), 0u);

  EXPECT_EQ(client().post("/api/runs", kLongRun).status, 409);  // fault held
  const auto reset = client().post("/api/reset");
  ASSERT_EQ(reset.status, 200) << reset.body.dump();
  EXPECT_EQ(reset.body["state"], "ready");
  daemon->signal(SIGTERM);
  EXPECT_EQ(daemon->wait(), 0);
}

TEST_F(DaemonProcessTest, ABadConfigExitsTwoNamingTheKeyAndCreatesNothing) {
  std::ifstream sim(std::string(WAVEBENCH_SOURCE_DIR) + "/configs/benches/sim.yaml");
  std::stringstream text;
  text << sim.rdbuf();
  auto yaml = text.str();
  const auto at = yaml.find("sync_period: \"1 ms\"");
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, std::string("sync_period: \"1 ms\"").size(), "sync_period: \"often\"");
  // Relative paths in the config resolve against its folder, which is now the test's.
  for (auto p = yaml.find("../twin/"); p != std::string::npos; p = yaml.find("../twin/")) {
    yaml.replace(p, 8, std::string(WAVEBENCH_SOURCE_DIR) + "/configs/twin/");
  }
  const auto bad = dir_ / "bad.yaml";
  std::ofstream(bad) << yaml;

  auto daemon = start(bad.string());
  EXPECT_EQ(port_, 0);
  const int status = daemon->wait();
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const auto err = daemon->stderr_text();
  EXPECT_NE(err.find("sync_period"), std::string::npos) << err;
  EXPECT_NE(err.find("often"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(runs_));
}

TEST_F(DaemonProcessTest, AMissingConfigFileExitsTwo) {
  auto daemon = start((dir_ / "nope.yaml").string());
  const int status = daemon->wait();
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(daemon->stderr_text().find("nope.yaml"), std::string::npos);
}

}  // namespace
}  // namespace wavebench::daemon::testing
