// A drive whose velocity unit differs from the config (issue #20) on the in-process simulated
// bench: the commissioning check's units row is red when the drive states its unit (0x60A9)
// and the config says another, and such a bench does not connect; the default drive and config stay
// green; and a run started anyway on a drive in rpm with a config in counts/s (which turns the
// input far faster than asked and reads 0x606C 2185× too low) trips on the input speed the output
// encoder measures, within 100 ms of bench time of crossing the limit.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "bench_test_support.hpp"
#include "wavebench/bench/bench_check.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::bench::testing {
namespace {

constexpr double kRadPerSToRpm = 60 / (2 * std::numbers::pi);

// The shipped sim config with its simulated drive in `unit`, stating it in 0x60A8/0x60A9 or not.
BenchConfig drive_in(simdevices::DriveVelocityUnit unit, bool si_unit_objects,
                     const std::function<void(BenchConfig&)>& adjust = {}) {
  return sim_config([&](BenchConfig& b) {
    auto devices =
        b.simulated->devices ? *b.simulated->devices : simdevices::SimulatedBenchConfig{};
    devices.drive.velocity_unit = unit;
    devices.drive.si_unit_objects = si_unit_objects;
    b.simulated->devices = std::make_shared<const simdevices::SimulatedBenchConfig>(devices);
    if (adjust) adjust(b);
  });
}

const CheckRow& units_row(const CheckReport& report) {
  for (const auto& row : report.rows)
    if (row.item == "units") return row;
  throw std::runtime_error("no units row");
}

CheckReport check(const BenchConfig& config) {
  SimBench sim(config);
  auto report = check_bench(*canopen_bench_of(*sim.bench));
  std::printf("%s", format_check_table(report).c_str());
  sim.bench->disconnect();
  return report;
}

TEST(DriveUnitMismatch, RpmDriveStatingItAgainstACountsConfigIsARedUnitsRow) {
  const auto report = check(drive_in(simdevices::DriveVelocityUnit::kRpm, true));
  const auto& row = units_row(report);
  EXPECT_FALSE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("the drive says 0x60A9 = 0x00B44700 (rev/min)"), std::string::npos)
      << row.detail;
  EXPECT_NE(row.detail.find("drive.velocity_unit = counts/s (increments/s)"), std::string::npos)
      << row.detail;
}

TEST(DriveUnitMismatch, DeciRpmDriveAgainstAnRpmConfigIsARedUnitsRow) {
  const auto report =
      check(drive_in(simdevices::DriveVelocityUnit::kDeciRpm, true, [](BenchConfig& b) {
        b.drive.velocity_unit = parse_drive_unit("rpm", DriveQuantity::kVelocity);
        b.drive.acceleration_unit = parse_drive_unit("rpm/s", DriveQuantity::kAcceleration);
      }));
  const auto& row = units_row(report);
  EXPECT_FALSE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("0x60A9 = 0xFFB44700 (0.1 rev/min)"), std::string::npos) << row.detail;
  EXPECT_NE(row.detail.find("drive.velocity_unit = rpm"), std::string::npos) << row.detail;
}

TEST(DriveUnitMismatch, DriveStatingTheConfigsUnitsIsGreen) {
  const auto report = check(drive_in(simdevices::DriveVelocityUnit::kRpm, true, [](BenchConfig& b) {
    b.drive.velocity_unit = parse_drive_unit("rpm", DriveQuantity::kVelocity);
    b.drive.acceleration_unit = parse_drive_unit("rpm/s", DriveQuantity::kAcceleration);
  }));
  const auto& row = units_row(report);
  EXPECT_TRUE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("they agree"), std::string::npos) << row.detail;
  EXPECT_TRUE(report.all_green()) << format_check_table(report);
}

TEST(DriveUnitMismatch, ADriveStatingOtherUnitsIsNotConnectedSoNoRunStarts) {
  SimBench sim(drive_in(simdevices::DriveVelocityUnit::kRpm, true));
  try {
    sim.bench->connect();
    ADD_FAILURE() << "connected a drive stating rpm under a config in counts/s";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("0x60A9 = 0x00B44700 (rev/min)"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kUnconfigured);
  EXPECT_EQ(sim.drive_state(), simdevices::Cia402State::kSwitchOnDisabled);
  sim.bench->disconnect();
}

TEST(DriveUnitMismatch, DefaultDriveAndConfigAreGreen) {
  const auto report = check(sim_config());
  EXPECT_TRUE(units_row(report).ok) << units_row(report).detail;
  EXPECT_TRUE(report.all_green()) << format_check_table(report);
}

// The check with its bounded motion; the input travel the output encoder saw × N, at most.
struct MotionChecked {
  CheckReport report;
  double max_travel_rev = 0;
  BenchLifecycle state_after = BenchLifecycle::kUnconfigured;
  simdevices::Cia402State drive_after{};
};

MotionChecked check_with_motion(const BenchConfig& config) {
  SimBench sim(config);
  CheckOptions options;
  options.motion = true;
  MotionChecked out;
  out.report = check_bench(*canopen_bench_of(*sim.bench), options);
  std::printf("%s", format_check_table(out.report).c_str());
  out.state_after = sim.bench->state();
  out.drive_after = sim.drive_state();
  const auto& samples = sim.observer.samples;
  const double ratio = config.description.sense.ratio;
  for (const auto& s : samples)
    out.max_travel_rev =
        std::max(out.max_travel_rev, std::abs(s.theta_out_rad - samples.front().theta_out_rad) *
                                         ratio / (2 * std::numbers::pi));
  sim.bench->disconnect();
  return out;
}

void expect_off(const MotionChecked& c) {
  EXPECT_EQ(c.state_after, BenchLifecycle::kInactive);
  EXPECT_TRUE(c.drive_after == simdevices::Cia402State::kSwitchOnDisabled ||
              c.drive_after == simdevices::Cia402State::kReadyToSwitchOn);
}

TEST(DriveUnitMismatch, MotionFindsAnRpmDriveThatDoesNotStateItsUnitWithinTheBound) {
  const auto c = check_with_motion(drive_in(simdevices::DriveVelocityUnit::kRpm, false));
  const auto& row = units_row(c.report);
  EXPECT_FALSE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("the drive's velocity unit is likely rpm"), std::string::npos)
      << row.detail;
  std::printf("input travel at most %.4f rev\n", c.max_travel_rev);
  EXPECT_LE(c.max_travel_rev, 0.2) << "beyond the check's bounded motion";
  expect_off(c);
}

TEST(DriveUnitMismatch, MotionFindsADeciRpmDriveAgainstAnRpmConfig) {
  const auto c = check_with_motion(
      drive_in(simdevices::DriveVelocityUnit::kDeciRpm, false, [](BenchConfig& b) {
        b.drive.velocity_unit = parse_drive_unit("rpm", DriveQuantity::kVelocity);
        b.drive.acceleration_unit = parse_drive_unit("rpm/s", DriveQuantity::kAcceleration);
      }));
  const auto& row = units_row(c.report);
  EXPECT_FALSE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("likely 0.1 rpm"), std::string::npos) << row.detail;
  EXPECT_LE(c.max_travel_rev, 0.2);
  expect_off(c);
}

TEST(DriveUnitMismatch, MotionOnTheDefaultDriveIsGreenAndTheDriveIsOffAfter) {
  const auto c = check_with_motion(sim_config());
  const auto& row = units_row(c.report);
  EXPECT_TRUE(row.ok) << row.detail;
  EXPECT_NE(row.detail.find("the units agree"), std::string::npos) << row.detail;
  EXPECT_TRUE(c.report.all_green()) << format_check_table(c.report);
  EXPECT_LE(c.max_travel_rev, 0.2);
  expect_off(c);
}

// Bench time at which the bench was first seen in fault, from the observer.
struct FaultWatch : SampleObserver {
  Bench* bench = nullptr;
  double tripped_s = -1;
  void on_sample(const storage::SyncSample& s) noexcept override {
    if (tripped_s < 0 && bench->state() == BenchLifecycle::kFault)
      tripped_s = static_cast<double>(s.receive_time_ns) * 1e-9;
  }
};

TEST(DriveUnitMismatch, RunStartedAnywayTripsOnTheEncoderSpeedWithin100Ms) {
  const double limit_rpm = 1000;
  // Only the input speed limit: a following-error or TE limit must not be what stops it here.
  auto config = drive_in(simdevices::DriveVelocityUnit::kRpm, false, [&](BenchConfig& b) {
    b.description.limits = {};
    b.description.limits.max_input_speed_rad_s = limit_rpm / kRadPerSToRpm;
  });
  SimBench sim(config);
  sim.bench->connect();
  FaultWatch watch;
  watch.bench = sim.bench.get();
  sim.bench->add_observer(watch);
  procedures::DynamicTeOptions o;  // 100 "rpm" written in counts/s: 218453 rpm to this drive
  o.output_revolutions = 1;
  o.run_in_s = 1;
  procedures::DynamicTeProcedure procedure(o);
  std::string reason;
  try {
    procedure.run(*sim.bench);
  } catch (const BenchAborted& e) {
    reason = e.what();
  }
  sim.bench->remove_observer(watch);
  const auto fault = sim.bench->fault_reason();
  sim.bench->disconnect();
  std::printf("tripped: %s\n", fault.c_str());
  EXPECT_NE(fault.find("input speed measured by the output encoder"), std::string::npos) << fault;
  ASSERT_GE(watch.tripped_s, 0) << "the run was not stopped";

  // The first crossing of the limit by the encoder-measured input speed (2 ms differences).
  const auto& samples = sim.observer.samples;
  const double ratio = config.description.sense.ratio;
  double crossed_s = -1, peak_rpm = 0;
  for (std::size_t k = 2; k < samples.size(); ++k) {
    const auto& a = samples[k - 2];
    const auto& b = samples[k];
    if (!a.valid(storage::kThetaOutValid) || !b.valid(storage::kThetaOutValid)) continue;
    const double dt = static_cast<double>(b.receive_time_ns - a.receive_time_ns) * 1e-9;
    if (dt <= 0) continue;
    const double rpm = std::abs(b.theta_out_rad - a.theta_out_rad) / dt * ratio * kRadPerSToRpm;
    peak_rpm = std::max(peak_rpm, rpm);
    if (crossed_s < 0 && rpm > limit_rpm) crossed_s = static_cast<double>(b.receive_time_ns) * 1e-9;
  }
  std::printf("crossed %.1f rpm at %.4f s, tripped at %.4f s, peak %.0f rpm\n", limit_rpm,
              crossed_s, watch.tripped_s, peak_rpm);
  ASSERT_GE(crossed_s, 0);
  EXPECT_LE(watch.tripped_s - crossed_s, 0.1);
  EXPECT_GE(watch.tripped_s - crossed_s, -0.01);
}

}  // namespace
}  // namespace wavebench::bench::testing
