#pragma once
// An in-process daemon on an ephemeral port with the fake bench and the fake run launcher, and
// a client holding its token.

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <thread>

#include "fake_bench.hpp"
#include "fake_run_launcher.hpp"
#include "test_dir.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/daemon/daemon_client.hpp"

namespace wavebench::daemon::testing {

inline constexpr const char* kToken = "0123456789abcdef0123456789abcdef";

class DaemonFixture : public ::testing::Test {
 public:
  void SetUp() override {
    dir_ = fresh_test_dir();
    start_daemon();
  }
  void TearDown() override { daemon_.reset(); }

  void start_daemon(bool fail_connect = false) {
    DaemonSetup setup;
    setup.bench_factory = [this, fail_connect] {
      auto bench = std::make_unique<FakeBench>(fail_connect);
      bench_ = bench.get();
      return bench;
    };
    setup.launcher = std::make_unique<FakeRunLauncher>();
    setup.runs_dir = dir_ / "runs";
    setup.port = 0;
    setup.token = kToken;
    setup.config_text = "name: fake\n";
    setup.logins = logins_;
    daemon_ = std::make_unique<Daemon>(std::move(setup));
    daemon_->start();
  }

  std::string url() const { return "http://127.0.0.1:" + std::to_string(daemon_->port()); }
  DaemonClient client(const std::string& token = kToken) const { return {url(), token}; }

  // Polls `done` (a guard against hanging, not a timing assertion).
  static bool eventually(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return done();
  }

  // Starts a run that only ends when aborted, and waits until some of its samples are on disk.
  std::string start_endless_run() {
    const auto reply =
        client().post("/api/runs", {{"procedure", "dynamic"}, {"options", {{"seconds", 1e6}}}});
    EXPECT_EQ(reply.status, 201) << reply.body.dump();
    const auto id = reply.body.value("run_id", std::string());
    EXPECT_TRUE(eventually([&] {
      const auto samples = client().get("/api/runs/" + id + "/samples?limit=1");
      return samples.ok() && samples.body.value("total", 0) > 0;
    }));
    return id;
  }

  bool run_finished() const {
    const auto status = client().get("/api/status");
    return status.ok() && status.body["run"].is_null();
  }

  std::filesystem::path dir_;
  std::unique_ptr<Daemon> daemon_;
  FakeBench* bench_ = nullptr;
  LoginSetup logins_;  // accounts and session timeouts, set before start_daemon()
};

}  // namespace wavebench::daemon::testing
