// configs/eds/*.eds against the simulated devices' object dictionaries, both ways: every object
// of the simulated OD is in the EDS with the same type, access and PDO mapping, and every
// object the EDS lists exists in the OD; and the bench's used objects agree with each EDS.
#include <gtest/gtest.h>

#include <span>
#include <string>

#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/eds.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/simdevices/output_encoder.hpp"
#include "wavebench/simdevices/servo_drive.hpp"
#include "wavebench/simdevices/torque_sensor.hpp"

namespace wavebench {
namespace {

using canopen::Eds;
using canopen::EdsAccess;
using simdevices::Access;

// A shipped EDS reads without a single warning: it is the example others are measured against.
canopen::Eds load(const char* name) {
  auto eds = Eds::load(std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "eds" / name);
  for (const auto& w : eds.warnings()) ADD_FAILURE() << w;
  return eds;
}

EdsAccess eds_access(Access a) {
  switch (a) {
    case Access::kReadOnly:
      return EdsAccess::kRo;
    case Access::kWriteOnly:
      return EdsAccess::kWo;
    case Access::kReadWrite:
      return EdsAccess::kRw;
    case Access::kConst:
      return EdsAccess::kConst;
  }
  return EdsAccess::kRo;
}

std::string where(std::uint16_t index, std::uint8_t sub) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X:%u", index, sub);
  return buf;
}

void expect_agree(const simdevices::ObjectDictionary& od, const Eds& eds, std::uint8_t node) {
  std::size_t od_objects = 0;
  od.for_each([&](std::uint16_t index, std::uint8_t sub, const simdevices::OdEntry& e) {
    ++od_objects;
    const auto* o = eds.find(index, sub);
    ASSERT_NE(o, nullptr) << where(index, sub) << " " << e.name << " missing from " << eds.source();
    EXPECT_EQ(o->data_type, static_cast<std::uint16_t>(e.type)) << where(index, sub);
    EXPECT_EQ(o->access, eds_access(e.access)) << where(index, sub);
    EXPECT_EQ(o->pdo_mapping, e.pdo_mappable) << where(index, sub);
    // Integer defaults: the factory value of the simulated device.
    const auto size = simdevices::data_type_size(e.type);
    if (size > 0 && !o->default_value.empty() && e.type != simdevices::DataType::kReal32 &&
        e.type != simdevices::DataType::kReal64 && !(index == 0x1018 && sub == 4)) {
      std::uint64_t raw = 0;
      for (std::size_t i = 0; i < size; ++i)
        raw |= static_cast<std::uint64_t>(e.default_value[i]) << (8 * i);
      const auto expected = *eds.default_integer(*o, node);
      const std::uint64_t mask = size == 8 ? ~0ULL : (1ULL << (8 * size)) - 1;
      EXPECT_EQ(raw, static_cast<std::uint64_t>(expected) & mask) << where(index, sub);
    }
  });
  for (const auto& [key, o] : eds.objects()) {
    EXPECT_NE(od.find(o.index, o.sub), nullptr)
        << where(o.index, o.sub) << " " << o.name << " is in " << eds.source()
        << " but not in the simulated device";
  }
  EXPECT_EQ(eds.objects().size(), od_objects);
}

simdevices::FrameSink no_frames() {
  return [](std::uint32_t, std::span<const std::uint8_t>) {};
}

TEST(EdsSimDevices, ServoDriveAgreesBothWays) {
  simdevices::Cia402ServoDrive drive(simdevices::ServoDriveConfig{}, no_frames());
  const auto eds = load("servo_drive.eds");
  expect_agree(drive.od(), eds, 1);
  EXPECT_TRUE(canopen::check_against_eds(canopen::Cia402Drive::used_objects(), eds).empty());
}

TEST(EdsSimDevices, OutputEncoderAgreesBothWays) {
  simdevices::Cia406Encoder encoder(simdevices::EncoderConfig{}, no_frames());
  const auto eds = load("output_encoder.eds");
  expect_agree(encoder.od(), eds, 3);
  EXPECT_TRUE(canopen::check_against_eds(canopen::Cia406Encoder::used_objects(), eds).empty());
}

TEST(EdsSimDevices, TorqueSensorAgreesBothWays) {
  simdevices::TorqueSensor sensor(simdevices::TorqueSensorConfig{}, no_frames());
  const auto eds = load("torque_sensor.eds");
  expect_agree(sensor.od(), eds, 4);
  const canopen::TorqueSensorConfig config{0x6130, 1, canopen::ValueType::i32, 1e-3, 0};
  EXPECT_TRUE(canopen::check_against_eds(canopen::TorqueSensor::used_objects(config), eds).empty());
  // Another process-value type than the EDS's is named.
  const canopen::TorqueSensorConfig f32{0x6130, 1, canopen::ValueType::f32, 1e-3, 0};
  const auto problems = canopen::check_against_eds(canopen::TorqueSensor::used_objects(f32), eds);
  ASSERT_EQ(problems.size(), 1U);
  EXPECT_NE(problems[0].find("0x6130:1 torque process value: EDS DataType INTEGER32"),
            std::string::npos)
      << problems[0];
}

}  // namespace
}  // namespace wavebench
