#pragma once
// The servo drive (CiA 402) as a bench device. State interfaces: theta_in [rad] (0x6064, unwrapped)
// and input_speed [rad/s] (0x606C), with the statusword and following error (0x60F4) beside
// them in the cycle's drive values. Command interfaces: input_position [rad] (profile
// position) and input_velocity [rad/s] (profile velocity), given through drive().
//
// Configuration: the drive's units and optional objects (drive_channels.hpp), TPDO1 statusword
// + position, TPDO2 velocity (+ following error where the drive has it), RPDO1 controlword
// (the quick stop's path, quick_stop_watch.hpp), and 0x6007 = 2 where the drive has it. A drive
// whose TPDO mapping is read-only (issue 20) keeps its own: the bench reads it back and takes
// each value from whichever TPDO carries it, at any position (canopen/pdo_adoption.hpp); the
// RPDO must still be writable (a fixed RPDO1 refuses the connection naming it).

#include <memory>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_device.hpp"
#include "wavebench/bench/drive_channels.hpp"
#include "wavebench/bench/input_shaft_scaling.hpp"
#include "wavebench/canopen/cia402_drive.hpp"

namespace wavebench::bench {

class Cia402DriveDevice final : public CanopenDevice {
 public:
  Cia402DriveDevice(canopen::NodeId node, DriveSettings settings);

  static canopen::PdoConfig position_pdo(canopen::NodeId node);
  static canopen::PdoConfig velocity_pdo(canopen::NodeId node, bool following_error = true);

  std::vector<storage::ChannelInfo> channels() const override;
  std::vector<CommandInterface> commands() const override;
  std::uint16_t profile() const noexcept override { return 0x0192; }
  std::vector<canopen::UsedObject> used_objects() const override;
  void configure(canopen::SdoClient& sdo) override;
  std::vector<canopen::PdoConfig> tpdos() const override;
  bool on_pdo(std::size_t i, const can::Frame& frame, CycleRecord& record) noexcept override;

  // After configure(): the drive's command path (by SDO) and what it was found to have.
  canopen::Cia402Drive& drive() { return *drive_; }
  bool configured() const noexcept { return drive_ != nullptr; }
  const DriveChannels& drive_channels() const noexcept { return channels_; }
  const DriveUnits& units() const noexcept { return channels_.units; }
  const DriveSettings& settings() const noexcept { return settings_; }
  // False when the drive lacks 0x6007 (an NMT stop may then leave its power stage on).
  bool abort_option_set() const noexcept { return abort_option_set_; }

 private:
  DriveSettings settings_;
  DriveChannels channels_;
  std::unique_ptr<canopen::Cia402Drive> drive_;
  Int32Unwrapper position_;
  bool abort_option_set_ = false;
};

}  // namespace wavebench::bench
