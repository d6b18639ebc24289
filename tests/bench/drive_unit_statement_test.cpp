// What the drive states of its units (0x60A8/0x60A9) against the config (issue #20).
#include "wavebench/bench/drive_unit_statement.hpp"

#include <gtest/gtest.h>

namespace wavebench::bench {
namespace {

DriveSettings config(const char* velocity) {
  DriveSettings s;
  s.velocity_unit = parse_drive_unit(velocity, DriveQuantity::kVelocity);
  return s;
}

TEST(DriveUnitStatement, DescribesSiUnitObjects) {
  EXPECT_EQ(describe_si_unit(0x00B44700), "rev/min");
  EXPECT_EQ(describe_si_unit(0xFFB44700), "0.1 rev/min");
  EXPECT_EQ(describe_si_unit(0x00B50300), "increments/s");
  EXPECT_EQ(describe_si_unit(0x00B50000), "increments");
  EXPECT_EQ(describe_si_unit(0xFD410000), "0.001 degree");
}

TEST(DriveUnitStatement, RpmDriveAgainstCountsConfigDisagreesNamingBoth) {
  DriveFactorGroup drive;
  drive.si_unit_velocity = 0x00B44700;
  const auto s = compare_drive_unit_statement(drive, config("counts/s"));
  EXPECT_TRUE(s.stated);
  EXPECT_FALSE(s.agree);
  EXPECT_NE(s.detail.find("the drive says 0x60A9 = 0x00B44700 (rev/min), drive.velocity_unit = "
                          "counts/s (increments/s)"),
            std::string::npos)
      << s.detail;
}

TEST(DriveUnitStatement, AgreeingUnitsAgree) {
  DriveFactorGroup drive;
  drive.si_unit_position = 0x00B50000;
  drive.si_unit_velocity = 0x00B44700;
  auto s = compare_drive_unit_statement(drive, config("rpm"));
  EXPECT_TRUE(s.agree) << s.detail;
  drive.si_unit_velocity = 0x00B50300;  // increments/s, 0x608F absent: the config's counts
  s = compare_drive_unit_statement(drive, config("counts/s"));
  EXPECT_TRUE(s.agree) << s.detail;
  drive.si_unit_velocity = 0xFFB44700;
  s = compare_drive_unit_statement(drive, config("0.1 rpm"));
  EXPECT_TRUE(s.agree) << s.detail;
}

TEST(DriveUnitStatement, DeciRpmDriveAgainstRpmConfigAndPositionMismatchDisagree) {
  DriveFactorGroup drive;
  drive.si_unit_velocity = 0xFFB44700;
  auto s = compare_drive_unit_statement(drive, config("rpm"));
  EXPECT_FALSE(s.agree) << s.detail;
  EXPECT_NE(s.detail.find("(0.1 rev/min), drive.velocity_unit = rpm"), std::string::npos)
      << s.detail;
  DriveFactorGroup degrees;
  degrees.si_unit_position = 0xFD410000;  // 0.001 degree, the config in counts
  s = compare_drive_unit_statement(degrees, config("counts/s"));
  EXPECT_FALSE(s.agree) << s.detail;
  EXPECT_NE(s.detail.find("0x60A8 = 0xFD410000 (0.001 degree), drive.position_unit = counts"),
            std::string::npos)
      << s.detail;
}

TEST(DriveUnitStatement, NoSiObjectsOrAFactorGroupConfigStateNothingToCompare) {
  auto s = compare_drive_unit_statement({}, config("counts/s"));
  EXPECT_FALSE(s.stated);
  EXPECT_TRUE(s.agree);
  DriveFactorGroup drive;
  drive.si_unit_velocity = 0x00B44700;
  auto fg = config("factor_group");
  fg.position_unit = parse_drive_unit("factor_group", DriveQuantity::kPosition);
  s = compare_drive_unit_statement(drive, fg);
  EXPECT_TRUE(s.agree) << s.detail;
}

}  // namespace
}  // namespace wavebench::bench
