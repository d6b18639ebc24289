#pragma once
// Assembles one SyncSample per SYNC cycle from the TPDOs that follow the SYNC (bench.md §1):
// drive TPDO1 (statusword, position), drive TPDO2 (velocity, and following error where the drive
// has 0x60F4), encoder TPDO1 (0x6004), torque sensor TPDO1 (its mapped value), and the brake's
// latest readback when it is fresh. A channel that did not arrive keeps its flag clear and is
// never filled in. Drive values are converted by DriveUnits.

#include <cstdint>
#include <optional>

#include "wavebench/bench/input_shaft_scaling.hpp"
#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::bench {

// Drive values of the cycle that are not in SyncSample but the safety checks need.
struct DriveCycleValues {
  bool status_valid = false;
  std::uint16_t statusword = 0;
  bool following_error_valid = false;
  double following_error_rad = 0;
};

class SampleAssembler {
 public:
  enum Frame : unsigned { kDrivePosition = 1, kDriveVelocity = 2, kEncoder = 4, kTorque = 8 };
  static constexpr unsigned kAllFrames = 15;

  // `following_error`: TPDO2 carries 0x60F4 after 0x606C (drive_velocity_pdo).
  SampleAssembler(DriveUnits units, canopen::Cia406Encoder& encoder,
                  const canopen::TorqueSensor& torque, bool following_error = true);

  static canopen::PdoConfig drive_position_pdo(std::uint8_t node);
  static canopen::PdoConfig drive_velocity_pdo(std::uint8_t node, bool following_error = true);
  static canopen::PdoConfig encoder_pdo(std::uint8_t node);
  canopen::PdoConfig torque_pdo(std::uint8_t node) const;

  void begin(std::uint64_t sync_index, std::int64_t time_ns);
  bool open() const noexcept { return open_; }
  // A frame of the open cycle; false when it is not one (or arrived twice, or malformed).
  bool on_drive_position(const can::Frame& frame);
  bool on_drive_velocity(const can::Frame& frame);
  bool on_encoder(const can::Frame& frame);
  bool on_torque(const can::Frame& frame);
  // The bench's channel devices: `count` extra channels, each from its own TPDO.
  void expect_extra(std::size_t count) noexcept { extra_expected_ = (1U << count) - 1U; }
  // Extra channel `i`'s TPDO of the open cycle, decoded by its device (nullopt: malformed).
  bool on_extra(std::size_t i, std::optional<double> value);
  bool all_frames() const noexcept {
    return arrived_ == kAllFrames && extra_arrived_ == extra_expected_;
  }
  void set_brake(double current_a, double torque_nm);
  // Closes the cycle and returns its sample.
  const storage::SyncSample& finish();

  const storage::SyncSample& sample() const noexcept { return sample_; }
  const DriveCycleValues& drive() const noexcept { return drive_; }
  // Frames expected per cycle and their payload bytes (for the bus-load estimate).
  static constexpr unsigned frames_per_cycle() { return 4; }
  unsigned payload_bytes_per_cycle() const;

 private:
  bool take(unsigned bit);

  DriveUnits units_;
  canopen::Cia406Encoder& encoder_;
  const canopen::TorqueSensor& torque_;
  canopen::PdoLayout drive_position_layout_;
  canopen::PdoLayout drive_velocity_layout_;
  canopen::PdoLayout torque_layout_;
  Int32Unwrapper drive_position_;
  storage::SyncSample sample_;
  DriveCycleValues drive_;
  unsigned arrived_ = 0;
  std::uint32_t extra_expected_ = 0;
  std::uint32_t extra_arrived_ = 0;
  bool open_ = false;
};

}  // namespace wavebench::bench
