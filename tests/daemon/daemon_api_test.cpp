// The daemon's API over HTTP against an in-process daemon (fake bench, fake executor).
#include <gtest/gtest.h>

#include "daemon_fixture.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {
namespace {

using DaemonApiTest = DaemonFixture;

TEST_F(DaemonApiTest, StatusShowsTheConnectedBenchReady) {
  const auto reply = client("").get("/api/status");
  ASSERT_EQ(reply.status, 200);
  EXPECT_EQ(reply.body["state"], "ready");
  EXPECT_EQ(reply.body["bench"]["name"], "fake");
  EXPECT_EQ(reply.body["bench"]["unit_serial"], "SN-FAKE-1");
  EXPECT_TRUE(reply.body["run"].is_null());
  EXPECT_TRUE(reply.body["fault_reason"].is_null());
  EXPECT_TRUE(reply.body["acquisition"].is_object());
}

TEST_F(DaemonApiTest, EverythingThatMovesHardwareNeedsTheToken) {
  for (const auto* target : {"/api/runs", "/api/abort", "/api/stop", "/api/reset"}) {
    for (const auto& token : {std::string(), std::string("wrong-token")}) {
      const auto reply = client(token).post(target, {{"procedure", "static"}});
      EXPECT_EQ(reply.status, 401) << target;
      EXPECT_EQ(reply.body["error"], "unauthorized") << target;
      EXPECT_FALSE(reply.body.value("detail", "").empty());
    }
  }
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);  // nothing was tripped
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());   // nothing was started
}

TEST_F(DaemonApiTest, ARunCompletesWithItsSamplesAndResults) {
  const auto started =
      client().post("/api/runs", {{"procedure", "static"}, {"options", {{"seconds", 0.3}}}});
  ASSERT_EQ(started.status, 201) << started.body.dump();
  const auto id = started.body["run_id"].get<std::string>();
  ASSERT_TRUE(eventually([&] { return run_finished(); }));

  const auto detail = client().get("/api/runs/" + id);
  ASSERT_EQ(detail.status, 200);
  EXPECT_EQ(detail.body["run"]["status"], "complete");
  EXPECT_EQ(detail.body["run"]["procedure"], "static");
  EXPECT_EQ(detail.body["run"]["unit_serial"], "SN-FAKE-1");
  EXPECT_EQ(detail.body["results"]["samples"], 300);
  EXPECT_EQ(detail.body["results"]["options"]["seconds"], 0.3);

  const auto samples = client().get("/api/runs/" + id + "/samples?from=100&limit=50");
  ASSERT_EQ(samples.status, 200);
  EXPECT_EQ(samples.body["total"], 300);
  ASSERT_EQ(samples.body["samples"].size(), 50u);
  EXPECT_EQ(samples.body["samples"][0]["index"], 100);
  EXPECT_EQ(samples.body["samples"][49]["index"], 149);
  EXPECT_TRUE(samples.body["samples"][0]["theta_in_rad"].is_number());

  const auto status = client().get("/api/status");
  EXPECT_EQ(status.body["state"], "ready");
  EXPECT_EQ(status.body["last_run"]["id"], id);
  EXPECT_EQ(status.body["last_run"]["status"], "complete");
}

TEST_F(DaemonApiTest, AbortEndsTheRunAbortedWithTheOperatorsReasonAndKeepsItsSamples) {
  const auto id = start_endless_run();
  const auto running = client().get("/api/status");
  EXPECT_EQ(running.body["state"], "running");
  EXPECT_EQ(running.body["run"]["id"], id);
  EXPECT_EQ(running.body["run"]["procedure"], "dynamic");

  const auto abort = client().post("/api/abort");
  ASSERT_EQ(abort.status, 200) << abort.body.dump();
  EXPECT_EQ(abort.body["run_id"], id);
  ASSERT_TRUE(eventually([&] { return run_finished(); }));

  const auto detail = client().get("/api/runs/" + id);
  EXPECT_EQ(detail.body["run"]["status"], "aborted");
  EXPECT_EQ(detail.body["run"]["reason"], "operator abort");
  const auto status = client().get("/api/status");
  EXPECT_EQ(status.body["state"], "fault");
  EXPECT_EQ(status.body["fault_reason"], "operator abort");
  EXPECT_EQ(bench_->brake_torque(), 0.0);

  const auto log = storage::read_sample_log(daemon_->store().paths(id).samples);
  EXPECT_GT(log.samples.size(), 0u);
  EXPECT_FALSE(log.corrupt_record);
  const auto samples = client().get("/api/runs/" + id + "/samples");
  EXPECT_EQ(samples.body["total"], log.samples.size());
}

TEST_F(DaemonApiTest, AFaultedBenchRefusesRunsUntilReset) {
  bench_->request_stop("over-torque");  // a real trip (a limit), not the operator's stop
  EXPECT_EQ(client().get("/api/status").body["state"], "fault");
  const auto refused = client().post("/api/runs", {{"procedure", "static"}});
  EXPECT_EQ(refused.status, 409);
  EXPECT_NE(refused.body["detail"].get<std::string>().find("over-torque"), std::string::npos);

  const auto reset = client().post("/api/reset");
  ASSERT_EQ(reset.status, 200) << reset.body.dump();
  EXPECT_EQ(reset.body["state"], "ready");
  EXPECT_EQ(client().post("/api/runs", {{"procedure", "static"}}).status, 201);
}

TEST_F(DaemonApiTest, OneRunAtATime) {
  const auto id = start_endless_run();
  const auto second = client().post("/api/runs", {{"procedure", "static"}});
  EXPECT_EQ(second.status, 409);
  EXPECT_NE(second.body["detail"].get<std::string>().find(id), std::string::npos);
  client().post("/api/abort");
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
}

TEST_F(DaemonApiTest, AbortWithoutARunIsAConflict) {
  const auto reply = client().post("/api/abort");
  EXPECT_EQ(reply.status, 409);
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);
}

TEST_F(DaemonApiTest, BadRunRequestsAre400NamingTheKey) {
  struct Case {
    std::string body, key;
  };
  for (const auto& c : std::vector<Case>{
           {"not json", "body"},
           {R"({"options": {}})", "procedure"},
           {R"({"procedure": 3})", "procedure"},
           {R"({"procedure": "static", "options": [1]})", "options"},
           {R"({"procedure": "static", "twin": "yes"})", "twin"},
           {R"({"procedure": "spin"})", "procedure"},                              // executor
           {R"({"procedure": "static", "options": {"seconds": -1}})", "seconds"},  // executor
       }) {
    // Text that is not JSON goes as a JSON string: not an object either way.
    const auto parsed = nlohmann::json::parse(c.body, nullptr, false);
    const auto reply =
        client().post("/api/runs", parsed.is_discarded() ? nlohmann::json(c.body) : parsed);
    EXPECT_EQ(reply.status, 400) << c.body;
    EXPECT_EQ(reply.body["error"], "bad request") << c.body;
    EXPECT_EQ(reply.body["detail"].get<std::string>().rfind(c.key, 0), 0u)
        << c.body << " -> " << reply.body.dump();
  }
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());  // nothing created
  EXPECT_EQ(client().get("/api/status").body["state"], "ready");
}

TEST_F(DaemonApiTest, RunsListFiltersByProcedureAndStatus) {
  for (const char* procedure : {"static", "lost-motion", "static"}) {
    ASSERT_EQ(client()
                  .post("/api/runs", {{"procedure", procedure}, {"options", {{"seconds", 0.05}}}})
                  .status,
              201);
    ASSERT_TRUE(eventually([&] { return run_finished(); }));
  }
  const auto aborted = start_endless_run();
  client().post("/api/abort");
  ASSERT_TRUE(eventually([&] { return run_finished(); }));

  EXPECT_EQ(client().get("/api/runs").body["runs"].size(), 4u);
  EXPECT_EQ(client().get("/api/runs?procedure=static").body["runs"].size(), 2u);
  const auto only_aborted = client().get("/api/runs?status=aborted").body["runs"];
  ASSERT_EQ(only_aborted.size(), 1u);
  EXPECT_EQ(only_aborted[0]["id"], aborted);
  EXPECT_EQ(client().get("/api/runs?limit=3").body["runs"].size(), 3u);
  const auto bad = client().get("/api/runs?status=done");
  EXPECT_EQ(bad.status, 400);
  EXPECT_EQ(bad.body["detail"].get<std::string>().rfind("status:", 0), 0u);
  EXPECT_EQ(client().get("/api/runs?colour=red").status, 400);
}

TEST_F(DaemonApiTest, UnknownRunsAndPathsAre404AndBadNumbers400) {
  EXPECT_EQ(client().get("/api/runs/20990101T000000.000000Z").status, 404);
  EXPECT_EQ(client().get("/api/runs/nope/samples").status, 404);
  EXPECT_EQ(client().get("/api/nothing").status, 404);
  EXPECT_EQ(client().get("/index.html").status, 404);
  EXPECT_EQ(client().post("/api/status").status, 405);
  const auto bad = client().get("/api/live?since=-3");
  EXPECT_EQ(bad.status, 400);
  EXPECT_EQ(bad.body["detail"].get<std::string>().rfind("since:", 0), 0u);
}

TEST_F(DaemonApiTest, LiveServesTheLatestSamplesInOrderWithoutRepeats) {
  const auto id = start_endless_run();
  std::uint64_t since = 0, seen = 0;
  std::uint64_t last_seq = 0;
  bool first = true;
  while (seen < 2000) {
    const auto reply = client().get("/api/live?since=" + std::to_string(since) + "&limit=500");
    ASSERT_EQ(reply.status, 200);
    // Anything skipped because the buffer moved on is reported as missed, not hidden.
    if (reply.body["missed"].get<std::uint64_t>() > 0) first = true;
    for (const auto& s : reply.body["samples"]) {
      const auto seq = s["seq"].get<std::uint64_t>();
      if (!first) {
        EXPECT_EQ(seq, last_seq + 1);
      }
      first = false;
      last_seq = seq;
      ++seen;
    }
    const auto next = reply.body["next"].get<std::uint64_t>();
    EXPECT_GE(next, since);
    if (!reply.body["samples"].empty()) {
      EXPECT_EQ(reply.body["samples"].back()["seq"].get<std::uint64_t>() + 1, next);
    }
    since = next;
  }
  client().post("/api/abort");
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
  (void)id;
}

TEST_F(DaemonApiTest, BetweenRunsTheBenchKeepsAcquiringForTheLiveView) {
  ASSERT_TRUE(eventually([&] { return client().get("/api/live").body["next"] > 100; }));
  const auto status = client().get("/api/status").body;
  EXPECT_EQ(status["state"], "ready");
  EXPECT_GT(status["acquisition"]["samples"], 0);
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());
}

TEST(DaemonStartup, ABenchThatDoesNotConnectLeavesTheDaemonIdleWithTheReason) {
  struct Fixture : DaemonFixture {
    void TestBody() override {}
  } f;
  f.dir_ = fresh_test_dir();
  f.start_daemon(/*fail_connect=*/true);
  const auto status = f.client().get("/api/status");
  EXPECT_EQ(status.body["state"], "idle");
  EXPECT_NE(status.body["connect_error"].get<std::string>().find("drive node 1"),
            std::string::npos);
  const auto refused = f.client().post("/api/runs", {{"procedure", "static"}});
  EXPECT_EQ(refused.status, 409);
}

TEST(DaemonStartup, AFactoryThatRejectsTheConfigFailsStart) {
  const auto dir = fresh_test_dir();
  DaemonSetup setup;
  setup.bench_factory = []() -> std::unique_ptr<bench::Bench> {
    throw std::invalid_argument("can.nodes.drive: got '200', expected 1..127");
  };
  setup.launcher = std::make_unique<FakeRunLauncher>();
  setup.runs_dir = dir / "runs";
  setup.port = 0;
  setup.token = kToken;
  Daemon d(std::move(setup));
  EXPECT_THROW(d.start(), std::invalid_argument);
}

TEST(DaemonStartup, RunsLeftRunningAreIncompleteAfterRestart) {
  const auto dir = fresh_test_dir();
  std::string id;
  {
    storage::RunStore store(dir / "runs", "test");
    id = store.create_run("dynamic", "SN-1", "x: 1\n");
  }
  DaemonSetup setup;
  setup.bench_factory = [] { return std::make_unique<FakeBench>(); };
  setup.launcher = std::make_unique<FakeRunLauncher>();
  setup.runs_dir = dir / "runs";
  setup.port = 0;
  setup.token = kToken;
  Daemon d(std::move(setup));
  d.start();
  DaemonClient c("http://127.0.0.1:" + std::to_string(d.port()), "");
  const auto runs = c.get("/api/runs?status=incomplete").body["runs"];
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["id"], id);
}

TEST(DaemonStartup, ShutdownAbortsTheActiveRunAndPutsTheBenchInItsSafeState) {
  struct Fixture : DaemonFixture {
    void TestBody() override {}
  } f;
  f.dir_ = fresh_test_dir();
  f.start_daemon();
  const auto id = f.start_endless_run();
  f.daemon_->shutdown("daemon stopped by SIGTERM");
  const auto run = f.daemon_->store().find_run(id);
  ASSERT_TRUE(run);
  EXPECT_EQ(run->status, storage::RunStatus::kAborted);
  EXPECT_EQ(run->reason, "daemon stopped by SIGTERM");
}

}  // namespace
}  // namespace wavebench::daemon::testing

namespace wavebench::daemon::testing {
namespace {

TEST_F(DaemonApiTest, BenchCheckIsRefusedDuringARunAndAbsentWithoutACheck) {
  // This daemon has no commissioning check: 503 naming it; only GET.
  auto reply = client().get("/api/bench/check");
  EXPECT_EQ(reply.status, 503) << reply.body.dump();
  EXPECT_NE(reply.body.value("detail", "").find("no commissioning check"), std::string::npos);
  EXPECT_EQ(client().post("/api/bench/check", nlohmann::json::object()).status, 405);

  const auto id = start_endless_run();
  reply = client().get("/api/bench/check");
  EXPECT_EQ(reply.status, 409) << reply.body.dump();
  EXPECT_NE(reply.body.value("detail", "").find("a run is active"), std::string::npos)
      << reply.body.dump();
  EXPECT_EQ(client().post("/api/abort", nlohmann::json::object()).status, 200);
  ASSERT_TRUE(eventually([&] { return run_finished(); })) << id;
}

}  // namespace
}  // namespace wavebench::daemon::testing
