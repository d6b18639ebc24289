// The simulated drive's units on the bus (issue #9): its objects in rpm, 0.1 rpm or factor-group
// units against hand-computed values, and an optional object it lacks answering 06020000.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "wavebench/simdevices/sdo_abort.hpp"
#include "wavebench/simdevices/servo_drive.hpp"

namespace wavebench::simdevices {
namespace {

Cia402ServoDrive make_drive(const ServoDriveConfig& c) {
  return Cia402ServoDrive(c, [](std::uint32_t, std::span<const std::uint8_t>) {});
}

// The drive's velocity actual 0x606C with the motor at `omega` rad/s.
std::int32_t velocity_actual(Cia402ServoDrive& d, double omega) {
  PlantState s{};
  s.omega_in = omega;
  d.observe(s);
  return d.od().get<std::int32_t>(0x606C, 0);
}

constexpr double kRpm = 2 * M_PI / 60;

TEST(DriveUnitsModel, RpmAndDeciRpmObjects) {
  ServoDriveConfig c;  // 131072 counts/rev, profile velocity 10 rev/s, acceleration 50 rev/s²
  c.velocity_unit = DriveVelocityUnit::kRpm;
  auto rpm = make_drive(c);
  EXPECT_EQ(rpm.od().get<std::uint32_t>(0x6081, 0), 600u);   // 10 rev/s
  EXPECT_EQ(rpm.od().get<std::uint32_t>(0x6083, 0), 3000u);  // 50 rev/s² in rpm/s
  EXPECT_EQ(rpm.od().get<std::uint32_t>(0x607F, 0), 3000u);  // max motor speed
  EXPECT_EQ(velocity_actual(rpm, 100 * kRpm), 100);
  c.velocity_unit = DriveVelocityUnit::kDeciRpm;
  auto deci = make_drive(c);
  EXPECT_EQ(deci.od().get<std::uint32_t>(0x6081, 0), 6000u);
  EXPECT_EQ(velocity_actual(deci, 100 * kRpm), 1000);
  EXPECT_FALSE(deci.od().find(0x6092, 1));  // no factor group objects
}

TEST(DriveUnitsModel, FactorGroupObjects) {
  ServoDriveConfig c;
  c.velocity_unit = DriveVelocityUnit::kFactorGroup;
  c.factor_group.gear_motor_revolutions = 3;
  c.factor_group.feed = 360000;
  auto d = make_drive(c);
  EXPECT_EQ(d.od().get<std::uint32_t>(0x6091, 1), 3u);
  EXPECT_EQ(d.od().get<std::uint32_t>(0x6092, 1), 360000u);
  EXPECT_EQ(d.od().get<std::uint32_t>(0x6090, 1), 131072u);
  // 120000 units per motor rev: 100 rpm = 200000 units/s; 10 rev/s profile = 1200000.
  EXPECT_EQ(velocity_actual(d, 100 * kRpm), 200000);
  EXPECT_EQ(d.od().get<std::uint32_t>(0x6081, 0), 1200000u);
  PlantState s{};
  s.theta_in = 2 * M_PI;
  d.observe(s);
  EXPECT_EQ(d.od().get<std::int32_t>(0x6064, 0), 120000);
}

TEST(DriveUnitsModel, AbsentOptionalObjectsAnswerObjectDoesNotExist) {
  ServoDriveConfig c;
  c.absent_objects = {0x60F4, 0x6077};
  auto d = make_drive(c);
  std::vector<std::uint8_t> out;
  EXPECT_EQ(d.od().read(0x60F4, 0, out), sdo_abort::kNoObject);
  EXPECT_EQ(d.od().read(0x6077, 0, out), sdo_abort::kNoObject);
  EXPECT_EQ(d.od().read(0x6064, 0, out), sdo_abort::kNone);
  // Mapping it into TPDO2 (COB-ID invalid, count 0, entry) is refused with the same abort.
  const auto bytes = [](std::uint32_t v) {
    return std::vector<std::uint8_t>{
        static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
        static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
  };
  ASSERT_EQ(d.od().write(0x1801, 1, bytes(0x80000281U)), sdo_abort::kNone);
  ASSERT_EQ(d.od().write(0x1A01, 0, std::vector<std::uint8_t>{0}), sdo_abort::kNone);
  EXPECT_EQ(d.od().write(0x1A01, 1, bytes(0x60F40020U)), sdo_abort::kNoObject);
  // A control period runs without the objects.
  PlantState s{};
  EXPECT_NO_THROW(d.control(s, 250e-6));
}

}  // namespace
}  // namespace wavebench::simdevices
