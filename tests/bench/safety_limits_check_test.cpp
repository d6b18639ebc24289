// Per-sample limits: each one trips with a sentence naming it; invalid channels are not judged.
#include "wavebench/bench/safety_limits_check.hpp"

#include <gtest/gtest.h>

namespace wavebench::bench {
namespace {

storage::SyncSample sample() {
  storage::SyncSample s;
  s.flags = storage::kAllChannelsValid;
  return s;
}

TEST(SafetyLimitsCheck, EachLimitTripsWithItsName) {
  SafetyLimits l;
  l.max_input_speed_rad_s = 10;
  l.max_brake_current_a = 2;
  l.max_brake_torque_nm = 50;
  l.max_measured_torque_nm = 60;
  l.max_following_error_rad = 1;
  l.max_coil_temperature_c = 80;
  l.max_te_excursion_rad = 1e-3;
  SafetyLimitsCheck check(l, {100, 1});
  DriveCycleValues drive;
  EXPECT_FALSE(check.check(sample(), drive, 20.0));

  auto s = sample();
  s.input_speed_rad_s = -11;
  EXPECT_NE(check.check(s, drive, {})->find("input speed"), std::string::npos);
  s = sample();
  s.brake_current_a = 2.5;
  EXPECT_NE(check.check(s, drive, {})->find("brake current"), std::string::npos);
  s = sample();
  s.brake_torque_nm = 51;
  EXPECT_NE(check.check(s, drive, {})->find("brake torque"), std::string::npos);
  s = sample();
  s.torque_nm = 61;
  EXPECT_NE(check.check(s, drive, {})->find("measured torque"), std::string::npos);
  drive.following_error_valid = true;
  drive.following_error_rad = 1.5;
  EXPECT_NE(check.check(sample(), drive, {})->find("following error"), std::string::npos);
  drive.following_error_rad = 0;
  EXPECT_NE(check.check(sample(), drive, 81.0)->find("coil temperature"), std::string::npos);
  check.reset_reference();
  // TE excursion from the first complete sample's TE (encoder zeros are arbitrary).
  s = sample();
  s.theta_out_rad = 0.5;  // TE0 = 0.5 rad
  EXPECT_FALSE(check.check(s, drive, {}));
  s.theta_out_rad = 0.5 + 0.9e-3;
  EXPECT_FALSE(check.check(s, drive, {}));
  s.theta_out_rad = 0.5 + 1.1e-3;
  EXPECT_NE(check.check(s, drive, {})->find("TE excursion"), std::string::npos);
}

TEST(SafetyLimitsCheck, InvalidChannelsAndZeroLimitsAreNotJudged) {
  SafetyLimits l;
  l.max_measured_torque_nm = 1;
  SafetyLimitsCheck check(l, {100, 1});
  auto s = sample();
  s.torque_nm = 5;
  s.flags &= ~storage::kTorqueValid;
  s.input_speed_rad_s = 1e6;  // no speed limit configured
  EXPECT_FALSE(check.check(s, {}, {}));
}

}  // namespace
}  // namespace wavebench::bench
