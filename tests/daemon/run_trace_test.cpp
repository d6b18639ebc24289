// GET /api/runs/{id}/trace and /twin over a synthetic run folder: the min/max envelope keeps a
// one-sample spike at any column count, small ranges come back at full resolution, bad
// parameters are 400 naming the key.
#include "wavebench/daemon/run_trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "daemon_fixture.hpp"
#include "test_dir.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {
namespace {

constexpr double kArcsecPerRad = 180.0 * 3600.0 / std::numbers::pi;
constexpr double kRatio = 100.0;
constexpr std::int64_t kPeriodNs = 1'000'000;  // 1 kHz

class RunTraceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_test_dir();
    store_ = std::make_unique<storage::RunStore>(dir_ / "runs", "test");
    id_ = store_->create_run("dynamic", "SN-1", "bench: test\n");
  }

  // n samples at 1 kHz: torque = sin, theta_in = 0 so TE = theta_out; theta_out is 0 but for
  // `spike_at`, where it is 1e-4 rad (20.6 arcsec).
  void write_samples(std::size_t n, std::size_t spike_at) {
    storage::SampleLogWriter writer(store_->paths(id_).samples);
    for (std::size_t i = 0; i < n; ++i) {
      storage::SyncSample s;
      s.sync_counter = static_cast<std::uint32_t>(i % 256);
      s.receive_time_ns = 5'000'000'000 + static_cast<std::int64_t>(i) * kPeriodNs;
      s.theta_in_rad = 0;
      s.theta_out_rad = i == spike_at ? 1e-4 : 0.0;
      s.torque_nm = std::sin(0.01 * static_cast<double>(i));
      s.flags = storage::kThetaInValid | storage::kThetaOutValid | storage::kTorqueValid;
      writer.append(s);
    }
    writer.close();
    store_->write_results(id_, {{"gear", {{"ratio", kRatio}, {"direction_sign", 1}}}});
  }

  ApiResponse trace(const std::string& query) const {
    return run_trace(*store_, id_, parse_http_target("/api/runs/" + id_ + "/trace?" + query));
  }

  std::filesystem::path dir_;
  std::unique_ptr<storage::RunStore> store_;
  std::string id_;
};

double max_of(const nlohmann::json& values) {
  double m = -1e300;
  for (const auto& v : values)
    if (v.is_number()) m = std::max(m, v.get<double>());
  return m;
}

TEST_F(RunTraceTest, ASingleSampleSpikeSurvivesAtAnyColumnCount) {
  write_samples(200'000, 123'457);  // more than a batch, so columns are decimated in steps
  const double spike = 1e-4 * kArcsecPerRad;
  for (const int columns : {1, 2, 7, 100, 1000, 4000}) {
    const auto r = trace("channels=te_arcsec,torque&columns=" + std::to_string(columns));
    ASSERT_EQ(r.status, 200) << r.body.dump();
    EXPECT_FALSE(r.body["full_resolution"].get<bool>());
    EXPECT_EQ(r.body["samples_in_range"], 200'000);
    const auto& te = r.body["series"]["te_arcsec"];
    EXPECT_LE(te.size(), 2u * static_cast<std::size_t>(columns)) << columns;
    EXPECT_EQ(te.size(), r.body["t_s"].size());
    EXPECT_NEAR(max_of(te), spike, 1e-9) << columns;
    // The torque envelope reaches the sine's extremes too.
    EXPECT_NEAR(max_of(r.body["series"]["torque"]), 1.0, 1e-4) << columns;
  }
}

TEST_F(RunTraceTest, TheSpikeSurvivesAZoomAndASmallRangeIsFullResolution) {
  write_samples(200'000, 123'457);
  const auto zoom = trace("channels=te_arcsec&from_s=99.9995&to_s=150.0005&columns=10");
  ASSERT_EQ(zoom.status, 200) << zoom.body.dump();
  EXPECT_NEAR(max_of(zoom.body["series"]["te_arcsec"]), 1e-4 * kArcsecPerRad, 1e-9);
  EXPECT_EQ(zoom.body["samples_in_range"], 50'001);

  const auto fine = trace("channels=te_arcsec&from_s=123.4005&to_s=123.5005&columns=100");
  ASSERT_EQ(fine.status, 200);
  EXPECT_TRUE(fine.body["full_resolution"].get<bool>());
  ASSERT_EQ(fine.body["t_s"].size(), 100u);  // every sample of the range
  EXPECT_NEAR(fine.body["t_s"][0].get<double>(), 123.401, 1e-9);
  EXPECT_NEAR(max_of(fine.body["series"]["te_arcsec"]), 1e-4 * kArcsecPerRad, 1e-9);

  const auto empty = trace("from_s=500&to_s=600");
  ASSERT_EQ(empty.status, 200);
  EXPECT_TRUE(empty.body["t_s"].empty());
  EXPECT_NEAR(empty.body["duration_s"].get<double>(), 199.999, 1e-9);
}

TEST_F(RunTraceTest, AChannelThatDidNotArriveIsAGap) {
  write_samples(100, 1000);
  const auto r = trace("channels=brake_current");
  ASSERT_EQ(r.status, 200);
  EXPECT_TRUE(r.body["full_resolution"].get<bool>());
  ASSERT_EQ(r.body["series"]["brake_current"].size(), 100u);
  EXPECT_TRUE(r.body["series"]["brake_current"][0].is_null());
  EXPECT_EQ(r.body["channels"][0]["unit"], "A");
}

TEST_F(RunTraceTest, BadParametersAre400NamingTheKey) {
  write_samples(100, 1000);
  const struct {
    const char* query;
    const char* key;
  } cases[] = {
      {"columns=0", "columns:"},    {"columns=4001", "columns:"},
      {"columns=abc", "columns:"},  {"from_s=-1", "from_s:"},
      {"from_s=nan", "from_s:"},    {"to_s=1e12", "to_s:"},
      {"from_s=2&to_s=1", "to_s:"}, {"channels=te_arcsec,bogus", "channels:"},
      {"channels=", "channels:"},   {"channels=theta_in,,torque", "channels:"},
  };
  for (const auto& c : cases) {
    const auto r = trace(c.query);
    EXPECT_EQ(r.status, 400) << c.query;
    const auto detail = r.body.value("detail", "");
    EXPECT_EQ(detail.rfind(c.key, 0), 0u) << c.query << ": " << detail;
  }
  const auto unknown = trace("channels=bogus");
  EXPECT_NE(unknown.body["detail"].get<std::string>().find("te_arcsec, theta_in"),
            std::string::npos);
}

TEST_F(RunTraceTest, AnUnknownRunIs404) {
  const auto r = run_trace(*store_, "20260101T000000.000000Z", parse_http_target("/x"));
  EXPECT_EQ(r.status, 404);
}

TEST_F(RunTraceTest, TwinCurvesBeforeAndAfterCalibration) {
  write_samples(10, 1000);
  const auto dir = store_->paths(id_).dir;
  {
    std::ofstream out(dir / "twin.csv");
    out << "t,index,measured_te_arcsec,predicted_te_arcsec,residual_arcsec\n";
    for (int i = 0; i < 20'000; ++i) {
      const double measured = i == 777 ? 50.0 : 1.0;
      out << 80 + i * 0.001 << ',' << i << ',' << measured << ",0.5," << measured - 0.5 << '\n';
    }
    out << "100,20000,,0.5,\n";  // a measurement that did not compute
  }
  const auto r = run_twin_trace(*store_, id_, parse_http_target("/t?columns=50"));
  ASSERT_EQ(r.status, 200) << r.body.dump();
  EXPECT_TRUE(r.body["after"].is_null());
  const auto& before = r.body["before"];
  EXPECT_FALSE(before["full_resolution"].get<bool>());
  // The twin's times are the bench's: the default range is the file's, every column filled.
  EXPECT_EQ(before["t_s"].size(), 100u);
  EXPECT_NEAR(max_of(before["series"]["measured_te_arcsec"]), 50.0, 1e-9);
  EXPECT_NEAR(max_of(before["series"]["residual_arcsec"]), 49.5, 1e-9);
  EXPECT_NEAR(r.body["end_s"].get<double>(), 100.0, 1e-9);
  EXPECT_NEAR(r.body["start_s"].get<double>(), 80.0, 1e-9);

  EXPECT_EQ(run_twin_trace(*store_, id_, parse_http_target("/t?columns=0")).status, 400);
}

}  // namespace
}  // namespace wavebench::daemon::testing

namespace wavebench::daemon::testing {
namespace {

using RunTraceApiTest = DaemonFixture;

TEST_F(RunTraceApiTest, TheTraceIsServedOverHttpAndBadColumnsAre400) {
  const auto started =
      client().post("/api/runs", {{"procedure", "static"}, {"options", {{"seconds", 0.3}}}});
  ASSERT_EQ(started.status, 201) << started.body.dump();
  const auto id = started.body["run_id"].get<std::string>();
  ASSERT_TRUE(eventually([&] { return run_finished(); }));

  const auto trace = client().get("/api/runs/" + id + "/trace?channels=torque,theta_in&columns=10");
  ASSERT_EQ(trace.status, 200) << trace.body.dump();
  EXPECT_EQ(trace.body["samples_in_range"], 300);
  EXPECT_LE(trace.body["t_s"].size(), 20u);
  EXPECT_EQ(trace.body["series"]["theta_in"].size(), trace.body["t_s"].size());

  const auto bad = client().get("/api/runs/" + id + "/trace?columns=5000");
  EXPECT_EQ(bad.status, 400);
  EXPECT_EQ(bad.body["detail"].get<std::string>().rfind("columns: got '5000'", 0), 0u);
  EXPECT_EQ(client().get("/api/runs/" + id + "/twin").status, 200);
  EXPECT_EQ(client().get("/api/runs/nope/trace").status, 404);
}

}  // namespace
}  // namespace wavebench::daemon::testing
