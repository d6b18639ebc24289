// The manual panel's session (manual_session.hpp): the dead-man, the bounds, and how it shares
// the bench with runs and the stop; directly on a stand-in bench, and over HTTP through an
// in-process daemon.
#include "wavebench/daemon/manual_session.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <numbers>
#include <thread>

#include "daemon_fixture.hpp"
#include "fake_bench.hpp"

namespace wavebench::daemon::testing {
namespace {

constexpr double kRpm = 2 * std::numbers::pi / 60;

// The fake bench with power: activate/deactivate and a motion command move the lifecycle as
// the Bench contract says, and the commanded input speed is visible.
class PoweredBench : public FakeBench {
 public:
  PoweredBench() {
    limits_.max_input_speed_rad_s = 3000 * kRpm;
    limits_.max_brake_torque_nm = 95;
  }
  bench::BenchLifecycle state() const noexcept override {
    const auto base = FakeBench::state();
    return base == bench::BenchLifecycle::kInactive && powered_ ? bench::BenchLifecycle::kActive
                                                                : base;
  }
  void activate() override { powered_ = true; }
  void deactivate() noexcept override {
    powered_ = false;
    omega_ = 0;
    brake_ = 0;
    ++deactivations_;
  }
  void run_input_velocity(double omega) override {
    FakeBench::run_input_velocity(omega);
    powered_ = true;
    omega_ = omega;
  }
  void stop_motion() override {
    FakeBench::stop_motion();
    omega_ = 0;
  }
  void set_brake_torque(double torque, double ramp) override {
    FakeBench::set_brake_torque(torque, ramp);
    if (torque > 0) powered_ = true;
    brake_ = torque;
  }
  void move_input_to(double theta, double speed) override {
    FakeBench::move_input_to(theta, speed);
    powered_ = true;
    last_target_ = theta;
  }
  void request_stop(const std::string& reason) noexcept override {
    FakeBench::request_stop(reason);
    omega_ = 0;
  }

  bench::SafetyLimits limits_;
  bool powered_ = false;
  double omega_ = 0;
  double brake_ = 0;
  double last_target_ = 0;
  int deactivations_ = 0;
};

class ManualSessionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    bench_.connect();
    auto description = bench_.description();
    description.limits = bench_.limits_;
    description.max_brake_torque_nm = 100;
    session_.set_bench(description);
  }
  PoweredBench bench_;
  ManualSession session_{[] {}};
};

TEST_F(ManualSessionTest, AJogRunsOnlyWhileItIsRepeated) {
  ASSERT_FALSE(session_.jog(30));
  session_.serve(bench_);
  EXPECT_NEAR(bench_.omega_, 30 * kRpm, 1e-9);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kActive);
  EXPECT_TRUE(session_.engaged());

  // Repeats inside the timeout keep it going.
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_FALSE(session_.jog(30));
    session_.serve(bench_);
    EXPECT_NEAR(bench_.omega_, 30 * kRpm, 1e-9) << "repeat " << i;
  }
  // The dead-man: no repeat for longer than the jog timeout stops it and powers down (the
  // servo was switched on for the jog only).
  std::this_thread::sleep_for(ManualSession::kJogTimeout + std::chrono::milliseconds(50));
  session_.serve(bench_);
  EXPECT_EQ(bench_.omega_, 0);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kInactive);
  EXPECT_FALSE(session_.engaged());
  EXPECT_NE(session_.state().last_stop.find("no keep-alive"), std::string::npos)
      << session_.state().last_stop;
}

TEST_F(ManualSessionTest, AReleaseStopsAndAHeldServoKeepsHolding) {
  session_.servo(true);
  session_.serve(bench_);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kActive);
  ASSERT_FALSE(session_.jog(-20));
  session_.serve(bench_);
  EXPECT_NEAR(bench_.omega_, -20 * kRpm, 1e-9);
  EXPECT_FALSE(session_.stop("released"));
  session_.serve(bench_);
  EXPECT_EQ(bench_.omega_, 0);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kActive);  // asked for: holding
  session_.servo(false);
  session_.serve(bench_);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kInactive);
  EXPECT_FALSE(session_.engaged());
}

TEST_F(ManualSessionTest, AHeldServoGoesOffWithoutKeepAlives) {
  session_.servo(true);
  ASSERT_FALSE(session_.brake(5));
  session_.serve(bench_);
  EXPECT_EQ(bench_.brake_, 5);
  session_.keep_alive();
  session_.serve(bench_);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kActive);
  // Not waiting 5 s: the hold's deadline is what the keep-alive set, so a session whose last
  // keep-alive is that old is switched off; simulated by asking again after the timeout.
  std::this_thread::sleep_for(ManualSession::kHoldTimeout + std::chrono::milliseconds(50));
  session_.serve(bench_);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kInactive);
  EXPECT_EQ(bench_.brake_, 0);
  EXPECT_NE(session_.state().last_stop.find("servo switched off"), std::string::npos);
}

TEST_F(ManualSessionTest, OverLimitRequestsAreRefusedNamingKeyValueAndBound) {
  const auto fast = session_.jog(500);
  ASSERT_TRUE(fast);
  EXPECT_EQ(fast->status, 400);
  EXPECT_NE(fast->detail.find("speed_rpm: got 500"), std::string::npos) << fast->detail;
  EXPECT_NE(fast->detail.find("60 rpm"), std::string::npos) << fast->detail;
  for (double bad : {0.0, std::nan(""), std::numeric_limits<double>::infinity(), -61.0})
    EXPECT_TRUE(session_.jog(bad)) << bad;

  const auto brake = session_.brake(200);
  ASSERT_TRUE(brake);
  EXPECT_NE(brake->detail.find("torque_nm: got 200"), std::string::npos) << brake->detail;
  EXPECT_NE(brake->detail.find("95"), std::string::npos) << brake->detail;
  EXPECT_TRUE(session_.brake(-1));

  const auto far = session_.go_to(1000, 30);
  ASSERT_TRUE(far);
  EXPECT_NE(far->detail.find("angle_deg: got 1000"), std::string::npos) << far->detail;
  EXPECT_TRUE(session_.go_to(10, 0));    // speed 0
  EXPECT_TRUE(session_.go_to(10, -30));  // a go-to's speed has no sign

  // Nothing moved, nothing was switched on.
  session_.serve(bench_);
  EXPECT_EQ(bench_.omega_, 0);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kInactive);
  EXPECT_FALSE(session_.engaged());
}

TEST_F(ManualSessionTest, TheSafetyLimitBoundsThePanelsOwnLimit) {
  ManualSession slow{[] {}};
  auto description = bench_.description();
  description.limits.max_input_speed_rad_s = 20 * kRpm;
  slow.set_bench(description);
  EXPECT_NEAR(slow.state().max_speed_rpm, 20, 1e-9);
  EXPECT_TRUE(slow.jog(30));
  EXPECT_FALSE(slow.jog(20));
}

TEST_F(ManualSessionTest, AGoToMovesTheInputByRatioTimesTheOutputAngle) {
  bench_.idle_for(0.001);  // one sample: the output stands at 1e-4 rad
  ASSERT_FALSE(session_.go_to(1.0, 30));
  session_.serve(bench_);
  // N = 100, s = +1: one output degree is 100 input degrees from where the input stands.
  EXPECT_NEAR(bench_.last_target_, 100 * (1.0 * std::numbers::pi / 180 - 1e-4), 1e-9);
  EXPECT_EQ(bench_.state(), bench::BenchLifecycle::kInactive);  // not held afterwards
}

TEST_F(ManualSessionTest, ATripEndsManualControlSafely) {
  session_.servo(true);
  ASSERT_FALSE(session_.jog(30));
  session_.serve(bench_);
  bench_.request_stop("operator stop");
  session_.serve(bench_);
  EXPECT_FALSE(session_.engaged());
  EXPECT_FALSE(session_.state().servo_on);
  EXPECT_GE(bench_.deactivations_, 1);  // brake off, drive disabled
  EXPECT_NE(session_.state().last_stop.find("operator stop"), std::string::npos);
}

// Over HTTP through the daemon's bench thread.
using ManualApiTest = DaemonFixture;

TEST_F(ManualApiTest, ARunIsRefusedWhileTheServoIsOnAndTheStopEndsIt) {
  EXPECT_EQ(client().get("/api/status").body["servo"], "servo off");
  ASSERT_EQ(client().post("/api/manual/servo", {{"on", true}}).status, 200);
  // The servo is switched on by the bench thread: the stop below must meet it on (a stop that
  // comes while it is still being switched on only cancels the wish, and leaves no last stop).
  ASSERT_TRUE(
      eventually([&] { return client().get("/api/status").body["manual"]["servo_on"] == true; }));
  const auto run = client().post("/api/runs", {{"procedure", "static"}});
  EXPECT_EQ(run.status, 409) << run.body.dump();
  EXPECT_NE(run.body.value("detail", "").find("manual panel"), std::string::npos)
      << run.body.dump();

  ASSERT_EQ(client().post("/api/stop", nlohmann::json::object()).status, 200);
  // An operator stop ends manual control and leaves the bench inactive (not in fault): the
  // servo off, the brake off, the stop's reason kept as the panel's last stop.
  ASSERT_TRUE(eventually([&] {
    const auto s = client().get("/api/status").body;
    return s["manual"]["servo_on"] == false && s["manual"]["last_stop"].is_string() &&
           s["manual"]["last_stop"].get<std::string>().find("stopped by operator") !=
               std::string::npos &&
           s["lifecycle"] == "inactive";
  }));
  const auto status = client().get("/api/status").body;
  EXPECT_EQ(status["servo"], "servo off") << status.dump();
  EXPECT_EQ(status["brake"], "brake off");
  // Nothing the panel wanted before the stop powers the servo again.
  for (int i = 0; i < 5; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_EQ(client().get("/api/status").body["lifecycle"], "inactive");
  }
}

TEST_F(ManualApiTest, ThePanelCannotActDuringARunAndBadBodiesAreRefused) {
  const auto id = start_endless_run();
  const auto jog = client().post("/api/manual/jog", {{"speed_rpm", 10}});
  EXPECT_EQ(jog.status, 409) << jog.body.dump();
  EXPECT_NE(jog.body.value("detail", "").find("a run is active"), std::string::npos);
  ASSERT_EQ(client().post("/api/abort", nlohmann::json::object()).status, 200);
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
  ASSERT_EQ(client().post("/api/reset", nlohmann::json::object()).status, 200);

  const auto fast = client().post("/api/manual/jog", {{"speed_rpm", 500}});
  EXPECT_EQ(fast.status, 400);
  EXPECT_NE(fast.body.value("detail", "").find("speed_rpm: got 500"), std::string::npos)
      << fast.body.dump();
  EXPECT_EQ(client().post("/api/manual/jog", {{"speed", 10}}).status, 400);
  EXPECT_EQ(client().post("/api/manual/jog", {{"speed_rpm", "10"}}).status, 400);
  EXPECT_EQ(client().post("/api/manual/servo", {{"on", 1}}).status, 400);
  EXPECT_EQ(client().post("/api/manual/launch", nlohmann::json::object()).status, 404);
  EXPECT_EQ(client("").post("/api/manual/jog", {{"speed_rpm", 10}}).status, 401);
  EXPECT_EQ(client().get("/api/manual/jog").status, 405);
}

}  // namespace
}  // namespace wavebench::daemon::testing
