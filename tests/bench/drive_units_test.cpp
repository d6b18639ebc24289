// The drive's units (issue #9): DriveUnits, the unit names of the bench config and the factor
// group's derivation against hand-computed values, and the refusals of bad names and factors.
#include "wavebench/bench/drive_units.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/drive_factor_group.hpp"
#include "wavebench/bench/drive_unit_choice.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::bench {
namespace {

constexpr double kRpm = 2 * std::numbers::pi / 60;  // rad/s per rpm

std::string error_of(const DriveFactorGroup& g) {
  try {
    derive_factor_group_units(g);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(DriveUnits, CountsAreTheMotorEncodersIncrements) {
  const DriveUnits u(131072);
  // 100 rpm = 100/60 rev/s × 131072 = 218453.33 counts/s.
  EXPECT_EQ(u.velocity_value(100 * kRpm, "v"), 218453);
  EXPECT_EQ(u.position_value(2 * std::numbers::pi, "p"), 131072);
  // 50 rev/s² = 6553600 counts/s².
  EXPECT_EQ(u.acceleration_value(50 * 2 * std::numbers::pi, "a"), 6553600u);
  EXPECT_NEAR(u.angle(65536), std::numbers::pi, 1e-12);
  EXPECT_NEAR(u.speed(131072), 2 * std::numbers::pi, 1e-12);
}

TEST(DriveUnits, FixedUnitsFromTheirNames) {
  const auto per_rev = [](const char* text, DriveQuantity q) {
    return parse_drive_unit(text, q).units_per_rev(131072);
  };
  const DriveUnits rpm(131072, per_rev("rpm", DriveQuantity::kVelocity),
                       per_rev("rpm/s", DriveQuantity::kAcceleration));
  EXPECT_EQ(rpm.velocity_value(100 * kRpm, "v"), 100);
  EXPECT_EQ(rpm.velocity_value(-100 * kRpm, "v"), -100);
  EXPECT_EQ(rpm.acceleration_value(50 * 2 * std::numbers::pi, "a"), 3000u);
  EXPECT_NEAR(rpm.speed(100), 100 * kRpm, 1e-12);

  const DriveUnits deci(131072, per_rev("0.1 rpm", DriveQuantity::kVelocity),
                        per_rev("0.1 rpm/s", DriveQuantity::kAcceleration));
  EXPECT_EQ(deci.velocity_value(100 * kRpm, "v"), 1000);
  EXPECT_NEAR(deci.speed(1000), 100 * kRpm, 1e-12);

  const DriveUnits rad(per_rev("0.001 deg", DriveQuantity::kPosition),
                       per_rev("rad/s", DriveQuantity::kVelocity),
                       per_rev("rad/s²", DriveQuantity::kAcceleration));
  EXPECT_EQ(rad.velocity_value(100 * kRpm, "v"), 10);  // 10.47 rad/s
  EXPECT_EQ(rad.position_value(std::numbers::pi / 2, "p"), 90000);
  EXPECT_EQ(rad.acceleration_value(12.4, "a"), 12u);
  EXPECT_EQ(rad.acceleration_value(0.01, "a"), 1u);  // never 0

  EXPECT_EQ(parse_drive_unit("factor_group", DriveQuantity::kVelocity).kind,
            DriveUnitChoice::Kind::kFactorGroup);
  EXPECT_EQ(parse_drive_unit("counts/s2", DriveQuantity::kAcceleration).kind,
            DriveUnitChoice::Kind::kCounts);
}

TEST(DriveUnits, ValuesOutsideTheObjectsRangeNameWhatAndTheValue) {
  const DriveUnits u(131072);
  try {
    u.position_value(1e6, "move_input_to target");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("move_input_to target = 1e+06 rad"), std::string::npos) << m;
    EXPECT_NE(m.find("INTEGER32"), std::string::npos) << m;
  }
  EXPECT_THROW(u.velocity_value(NAN, "v"), std::invalid_argument);
  EXPECT_THROW(DriveUnits(0, 1, 1), std::invalid_argument);
}

TEST(DriveUnits, BadUnitNamesAreRefusedSayingWhatIsExpected) {
  for (const char* bad : {"rmp", "", "0 rpm", "-1 rpm", "0.1 counts/s", "rpm/s", "1e400 rpm",
                          "counts", "rad/s²", "fast"}) {
    try {
      parse_drive_unit(bad, DriveQuantity::kVelocity);
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("rpm"), std::string::npos) << m;
      EXPECT_NE(m.find("factor_group"), std::string::npos) << m;
    }
  }
  EXPECT_THROW(parse_drive_unit("rpm", DriveQuantity::kPosition), std::invalid_argument);
  EXPECT_THROW(parse_drive_unit("rpm", DriveQuantity::kAcceleration), std::invalid_argument);
}

TEST(DriveFactorGroup, VelocityEncoder4096FeedOneRevolutionIsRevolutionsPerSecond) {
  // 0x6090 = 4096 inc/s per rev/s, 0x6091 = 1/1, 0x6092 = 1 per shaft rev, no SI objects: the
  // position unit is one driving shaft revolution, the velocity unit one rev/s (the encoder's
  // resolution cancels: user = increments × feed / (resolution × gear)). 100 rpm = 1.667.
  DriveFactorGroup g;
  g.velocity_encoder_resolution = Fraction{4096, 1};
  g.gear_ratio = Fraction{1, 1};
  g.feed_constant = Fraction{1, 1};
  const auto f = derive_factor_group_units(g);
  EXPECT_DOUBLE_EQ(f.position_per_rev, 1);
  EXPECT_DOUBLE_EQ(f.velocity_per_rev_s, 1);
  const DriveUnits u(f.position_per_rev, f.velocity_per_rev_s, f.acceleration_per_rev_s2);
  EXPECT_EQ(u.velocity_value(100 * kRpm, "v"), 2);  // 1.667 rounded: a unit too coarse

  // The same drive with 0x60A9 = rev/min (0x00B44700): 100 rpm is 100.
  g.si_unit_velocity = 0x00B44700U;
  const auto per_min = derive_factor_group_units(g);
  EXPECT_DOUBLE_EQ(per_min.velocity_per_rev_s, 60);
  EXPECT_EQ(DriveUnits(1, per_min.velocity_per_rev_s, 1).velocity_value(100 * kRpm, "v"), 100);

  // Without a feed constant positions are 0x608F increments and velocities 0x6090 increments
  // per s: 100 rpm = 100/60 × 4096 = 6826.67.
  DriveFactorGroup inc;
  inc.position_encoder_resolution = Fraction{4096, 1};
  inc.velocity_encoder_resolution = Fraction{4096, 1};
  const auto i = derive_factor_group_units(inc);
  EXPECT_DOUBLE_EQ(i.position_per_rev, 4096);
  EXPECT_DOUBLE_EQ(i.velocity_per_rev_s, 4096);
  EXPECT_EQ(DriveUnits(i.position_per_rev, i.velocity_per_rev_s, i.acceleration_per_rev_s2)
                .velocity_value(100 * kRpm, "v"),
            6827);
}

TEST(DriveFactorGroup, GearAndFeedOfTheSimulatedFactorGroupDrive) {
  // configs/benches/sim-factor-group-drive.yaml: gear 3 motor revs per shaft rev, feed 360000
  // per shaft rev: 120000 units per motor rev; 100 rpm = 200000 units/s; 1 rad = 19098.6.
  DriveFactorGroup g;
  g.position_encoder_resolution = Fraction{131072, 1};
  g.velocity_encoder_resolution = Fraction{131072, 1};
  g.gear_ratio = Fraction{3, 1};
  g.feed_constant = Fraction{360000, 1};
  const auto f = derive_factor_group_units(g);
  EXPECT_DOUBLE_EQ(f.position_per_rev, 120000);
  EXPECT_DOUBLE_EQ(f.velocity_per_rev_s, 120000);
  EXPECT_DOUBLE_EQ(f.acceleration_per_rev_s2, 120000);
  const DriveUnits u(f.position_per_rev, f.velocity_per_rev_s, f.acceleration_per_rev_s2);
  EXPECT_EQ(u.velocity_value(100 * kRpm, "v"), 200000);
  EXPECT_EQ(u.position_value(1.0, "p"), 19099);
  EXPECT_NE(f.derivation.find("0x6092"), std::string::npos) << f.derivation;
}

TEST(DriveFactorGroup, SiUnitObjectsWithPrefixesAndGear) {
  // 0x60A8 = 0xFD410000: 10^-3 degree of the driving shaft; gear 5/2 motor revs per shaft rev:
  // 360000 / 2.5 = 144000 per motor rev. 0x60A9 = 0xFEB44700: 0.01 rev/min of the shaft:
  // 100 / 2.5 × 60 = 2400 per motor rev/s, so 100 rpm at the motor = 40 rpm = 4000.
  DriveFactorGroup g;
  g.gear_ratio = Fraction{5, 2};
  g.si_unit_position = 0xFD410000U;
  g.si_unit_velocity = 0xFEB44700U;
  const auto f = derive_factor_group_units(g);
  EXPECT_NEAR(f.position_per_rev, 144000, 1e-6);
  EXPECT_NEAR(f.velocity_per_rev_s, 2400, 1e-9);
  EXPECT_EQ(DriveUnits(f.position_per_rev, f.velocity_per_rev_s, f.acceleration_per_rev_s2)
                .velocity_value(100 * kRpm, "v"),
            4000);

  // 0.1 rpm (0xFFB44700), no gear: 600 per rev/s. rad/s (0x00100300): 2π per rev/s.
  DriveFactorGroup deci;
  deci.si_unit_velocity = 0xFFB44700U;
  deci.position_encoder_resolution = Fraction{131072, 1};
  EXPECT_NEAR(derive_factor_group_units(deci).velocity_per_rev_s, 600, 1e-9);
  deci.si_unit_velocity = 0x00100300U;
  EXPECT_NEAR(derive_factor_group_units(deci).velocity_per_rev_s, 2 * std::numbers::pi, 1e-12);
  // Increments (0xB5) of 0x608F for position, of 0x6090 for velocity.
  DriveFactorGroup inc;
  inc.position_encoder_resolution = Fraction{10000, 1};
  inc.velocity_encoder_resolution = Fraction{2500, 1};
  inc.si_unit_position = 0x00B50000U;
  inc.si_unit_velocity = 0x00B50300U;
  const auto i = derive_factor_group_units(inc);
  EXPECT_DOUBLE_EQ(i.position_per_rev, 10000);
  EXPECT_DOUBLE_EQ(i.velocity_per_rev_s, 2500);
}

TEST(DriveFactorGroup, ZeroNegativeAndUnknownFactorsAreRefusedNamingTheObject) {
  DriveFactorGroup g;
  g.gear_ratio = Fraction{1, 1};
  g.feed_constant = Fraction{0, 1};
  auto m = error_of(g);
  EXPECT_NE(m.find("0x6092:01 (feed constant, numerator) = 0"), std::string::npos) << m;
  EXPECT_NE(m.find("expected an UNSIGNED32 > 0"), std::string::npos) << m;

  g.feed_constant = Fraction{1000, 1};
  g.gear_ratio = Fraction{1, 0};
  m = error_of(g);
  EXPECT_NE(m.find("0x6091:02 (gear ratio, denominator) = 0"), std::string::npos) << m;

  g.gear_ratio = Fraction{0xFFFFFF9CU, 1};  // -100 as INTEGER32
  m = error_of(g);
  EXPECT_NE(m.find("0x6091:01"), std::string::npos) << m;
  EXPECT_NE(m.find("-100 as INTEGER32"), std::string::npos) << m;
  EXPECT_NE(m.find("positive"), std::string::npos) << m;

  g.gear_ratio = Fraction{1, 1};
  g.si_unit_velocity = 0x00B40500U;  // an unknown time unit
  m = error_of(g);
  EXPECT_NE(m.find("0x60A9 (SI unit velocity) = 0x00B40500"), std::string::npos) << m;

  g.si_unit_velocity.reset();
  g.si_unit_position = 0x00B40300U;  // a velocity unit in the position object
  m = error_of(g);
  EXPECT_NE(m.find("0x60A8"), std::string::npos) << m;

  EXPECT_NE(error_of(DriveFactorGroup{}).find("0x608F and 0x6092"), std::string::npos);
  DriveFactorGroup metres;
  metres.si_unit_position = 0xFD010000U;  // mm without a feed constant
  EXPECT_NE(error_of(metres).find("feed constant 0x6092"), std::string::npos);
}

std::string config_error(const std::string& drive_yaml) {
  try {
    parse_bench_config("drive:\n" + drive_yaml, ".");
  } catch (const config::ConfigError& e) {
    return e.key() + " | " + e.value() + " | " + e.expected();
  }
  return "(accepted)";
}

TEST(DriveUnitsConfig, KeysReadAndBadValuesNamed) {
  const auto c = parse_bench_config(
      "drive:\n  velocity_unit: \"0.1 rpm\"\n  acceleration_unit: rpm/s\n  position_unit: "
      "factor_group\n  torque_actual_scale: \"0.002 N*m\"\n",
      ".");
  EXPECT_DOUBLE_EQ(c.drive.velocity_unit.per_rev, 600);
  EXPECT_DOUBLE_EQ(c.drive.acceleration_unit.per_rev, 60);
  EXPECT_EQ(c.drive.position_unit.kind, DriveUnitChoice::Kind::kFactorGroup);
  ASSERT_TRUE(c.drive.torque_actual_nm_per_unit);
  EXPECT_DOUBLE_EQ(*c.drive.torque_actual_nm_per_unit, 0.002);
  const auto defaults = parse_bench_config("name: x\n", ".");
  EXPECT_EQ(defaults.drive.velocity_unit.kind, DriveUnitChoice::Kind::kCounts);
  EXPECT_FALSE(defaults.drive.torque_actual_nm_per_unit);

  auto m = config_error("  velocity_unit: rmp\n");
  EXPECT_EQ(m.substr(0, m.find(" | rmp | ")), "drive.velocity_unit") << m;
  EXPECT_NE(m.find("counts/s, rpm"), std::string::npos) << m;
  m = config_error("  position_unit: \"-5 deg\"\n");
  EXPECT_NE(m.find("drive.position_unit | -5 deg | counts, rev, deg, rad"), std::string::npos) << m;
  m = config_error("  acceleration_unit: rpm\n");
  EXPECT_NE(m.find("drive.acceleration_unit | rpm | "), std::string::npos) << m;
  m = config_error("  torque_actual_scale: \"0 N*m\"\n");
  EXPECT_NE(m.find("drive.torque_actual_scale | 0 N*m | rated"), std::string::npos) << m;
  m = config_error("  torque_actual_scale: \"3 rpm\"\n");
  EXPECT_NE(m.find("drive.torque_actual_scale | 3 rpm | "), std::string::npos) << m;
  m = config_error("  velocity_unit: [rpm]\n");
  EXPECT_NE(m.find("drive.velocity_unit"), std::string::npos) << m;
}

}  // namespace
}  // namespace wavebench::bench
