// Unit parsing against hand-computed SI values.
#include "wavebench/config/units.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Units, AnglesToRadians) {
  EXPECT_DOUBLE_EQ(parse_quantity("8 arcmin", Dimension::kAngle, "k"), 8.0 / 60.0 * kPi / 180.0);
  EXPECT_DOUBLE_EQ(parse_quantity("3600 arcsec", Dimension::kAngle, "k"), kPi / 180.0);
  EXPECT_DOUBLE_EQ(parse_quantity("180 deg", Dimension::kAngle, "k"), kPi);
  EXPECT_DOUBLE_EQ(parse_quantity("0.5 rev", Dimension::kAngle, "k"), kPi);
  EXPECT_DOUBLE_EQ(parse_quantity("1.5 rad", Dimension::kAngle, "k"), 1.5);
  EXPECT_DOUBLE_EQ(parse_quantity("1.5", Dimension::kAngle, "k"), 1.5);  // bare = SI
}

TEST(Units, SpeedsIncludingHzAsRevPerSecond) {
  EXPECT_DOUBLE_EQ(parse_quantity("2680 rpm", Dimension::kAngularSpeed, "k"),
                   2680.0 * 2.0 * kPi / 60.0);
  EXPECT_DOUBLE_EQ(parse_quantity("2 Hz", Dimension::kAngularSpeed, "k"), 4.0 * kPi);
  EXPECT_DOUBLE_EQ(parse_quantity("3 rad/s", Dimension::kAngularSpeed, "k"), 3.0);
  // Where a frequency is expected Hz stays Hz.
  EXPECT_DOUBLE_EQ(parse_quantity("2 Hz", Dimension::kFrequency, "k"), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity("60 kHz", Dimension::kFrequency, "k"), 60000.0);
}

TEST(Units, MechanicalQuantities) {
  EXPECT_DOUBLE_EQ(parse_quantity("12 um", Dimension::kLength, "k"), 12e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("80.4 mm", Dimension::kLength, "k"), 0.0804);
  EXPECT_DOUBLE_EQ(parse_quantity("60 N*m", Dimension::kTorque, "k"), 60.0);
  EXPECT_DOUBLE_EQ(parse_quantity("250 mN*m", Dimension::kTorque, "k"), 0.25);
  EXPECT_DOUBLE_EQ(parse_quantity("7.8e5 N*m/rad", Dimension::kStiffness, "k"), 7.8e5);
  EXPECT_NEAR(parse_quantity("1 N*m/arcmin", Dimension::kStiffness, "k"), 10800.0 / kPi, 1e-9);
  EXPECT_NEAR(parse_quantity("1 N*m/arcsec", Dimension::kStiffness, "k"), 648000.0 / kPi, 1e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("0.2839 kg*m^2", Dimension::kInertia, "k"), 0.2839);
  EXPECT_DOUBLE_EQ(parse_quantity("2200 g*cm^2", Dimension::kInertia, "k"), 2.2e-4);
  EXPECT_DOUBLE_EQ(parse_quantity("0.16 N*m*s/rad", Dimension::kDamping, "k"), 0.16);
}

TEST(Units, ElectricalThermalAndTime) {
  EXPECT_DOUBLE_EQ(parse_quantity("250 ms", Dimension::kTime, "k"), 0.25);
  EXPECT_DOUBLE_EQ(parse_quantity("20 us", Dimension::kTime, "k"), 20e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("500 mA", Dimension::kCurrent, "k"), 0.5);
  EXPECT_DOUBLE_EQ(parse_quantity("24 V", Dimension::kVoltage, "k"), 24.0);
  EXPECT_DOUBLE_EQ(parse_quantity("6 Ohm", Dimension::kResistance, "k"), 6.0);
  EXPECT_DOUBLE_EQ(parse_quantity("2.5 mH", Dimension::kInductance, "k"), 2.5e-3);
  EXPECT_DOUBLE_EQ(parse_quantity("0.52 N*m/A", Dimension::kTorqueConstant, "k"), 0.52);
  EXPECT_DOUBLE_EQ(parse_quantity("0.52 V*s/rad", Dimension::kBackEmfConstant, "k"), 0.52);
  EXPECT_DOUBLE_EQ(parse_quantity("80 degC", Dimension::kTemperature, "k"), 80.0);
  EXPECT_NEAR(parse_quantity("300 K", Dimension::kTemperature, "k"), 26.85, 1e-12);
  EXPECT_DOUBLE_EQ(parse_quantity("5 %", Dimension::kDimensionless, "k"), 0.05);
}

TEST(Units, TypographicSpellings) {
  EXPECT_DOUBLE_EQ(parse_quantity("60 N\xC2\xB7m", Dimension::kTorque, "k"), 60.0);
  EXPECT_DOUBLE_EQ(parse_quantity("60 N m", Dimension::kTorque, "k"), 60.0);
  EXPECT_DOUBLE_EQ(parse_quantity("12 \xC2\xB5m", Dimension::kLength, "k"), 12e-6);
  EXPECT_DOUBLE_EQ(parse_quantity("0.3 kg\xC2\xB7m\xC2\xB2", Dimension::kInertia, "k"), 0.3);
  EXPECT_DOUBLE_EQ(parse_quantity("6 \xCE\xA9", Dimension::kResistance, "k"), 6.0);
}

TEST(Units, WrongDimensionNamesKeyValueAndBothKinds) {
  try {
    parse_quantity("7.8e5 N*m", Dimension::kStiffness, "stiffness.k0");
    FAIL() << "a torque accepted as a stiffness";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "stiffness.k0");
    EXPECT_EQ(e.value(), "7.8e5 N*m");
    const std::string msg = e.what();
    EXPECT_NE(msg.find("stiffness.k0"), std::string::npos);
    EXPECT_NE(msg.find("7.8e5 N*m"), std::string::npos);
    EXPECT_NE(msg.find("N*m/rad"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a torque"), std::string::npos) << msg;
  }
}

TEST(Units, UnknownUnitAndMalformedNumber) {
  EXPECT_THROW(parse_quantity("8 furlongs", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("eight arcmin", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("1e999 rad", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("nan rad", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("inf", Dimension::kAngle, "k"), ConfigError);
  EXPECT_THROW(parse_quantity("2680 rpm", Dimension::kFrequency, "k"), ConfigError);
}

}  // namespace
}  // namespace wavebench::config
