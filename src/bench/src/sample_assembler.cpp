#include "wavebench/bench/sample_assembler.hpp"

#include <numbers>

#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::bench {
namespace {
const std::vector<canopen::PdoEntry> kDrivePositionMapping{{0x6041, 0, 16}, {0x6064, 0, 32}};
std::vector<canopen::PdoEntry> drive_velocity_mapping(bool following_error) {
  if (following_error) return {{0x606C, 0, 32}, {0x60F4, 0, 32}};
  return {{0x606C, 0, 32}};
}
}  // namespace

SampleAssembler::SampleAssembler(DriveUnits units, canopen::Cia406Encoder& encoder,
                                 const canopen::TorqueSensor& torque, bool following_error)
    : units_(units),
      encoder_(encoder),
      torque_(torque),
      drive_position_layout_(kDrivePositionMapping),
      drive_velocity_layout_(drive_velocity_mapping(following_error)),
      torque_layout_({canopen::PdoEntry::decode(torque.mapping_entry())}) {}

canopen::PdoConfig SampleAssembler::drive_position_pdo(std::uint8_t node) {
  return {canopen::tpdo_cob_id(1, node), 1, 0, kDrivePositionMapping};
}
canopen::PdoConfig SampleAssembler::drive_velocity_pdo(std::uint8_t node, bool following_error) {
  return {canopen::tpdo_cob_id(2, node), 1, 0, drive_velocity_mapping(following_error)};
}
canopen::PdoConfig SampleAssembler::encoder_pdo(std::uint8_t node) {
  return {canopen::tpdo_cob_id(1, node), 1, 0, {{0x6004, 0, 32}}};
}
canopen::PdoConfig SampleAssembler::torque_pdo(std::uint8_t node) const {
  return {
      canopen::tpdo_cob_id(1, node), 1, 0, {canopen::PdoEntry::decode(torque_.mapping_entry())}};
}

unsigned SampleAssembler::payload_bytes_per_cycle() const {
  return static_cast<unsigned>(drive_position_layout_.length_bytes() +
                               drive_velocity_layout_.length_bytes() + 4 +
                               torque_layout_.length_bytes());
}

void SampleAssembler::begin(std::uint64_t sync_index, std::int64_t time_ns) {
  sample_.sync_counter = static_cast<std::uint32_t>(sync_index % 240 + 1);
  sample_.flags = 0;
  sample_.receive_time_ns = time_ns;
  sample_.missed_before = 0;
  drive_.status_valid = false;
  drive_.following_error_valid = false;
  arrived_ = 0;
  extra_arrived_ = 0;
  sample_.extra_valid = 0;
  open_ = true;
}

bool SampleAssembler::take(unsigned bit) {
  if (!open_ || (arrived_ & bit) != 0) return false;
  arrived_ |= bit;
  return true;
}

bool SampleAssembler::on_drive_position(const can::Frame& frame) {
  if (!drive_position_layout_.fits(frame) || !take(kDrivePosition)) return false;
  drive_.statusword = static_cast<std::uint16_t>(drive_position_layout_.raw(frame, 0));
  drive_.status_valid = true;
  const auto raw = static_cast<std::int32_t>(drive_position_layout_.signed_value(frame, 1));
  sample_.theta_in_rad = units_.angle(static_cast<double>(drive_position_.update(raw)));
  sample_.flags |= storage::kThetaInValid;
  return true;
}

bool SampleAssembler::on_drive_velocity(const can::Frame& frame) {
  if (!drive_velocity_layout_.fits(frame) || !take(kDriveVelocity)) return false;
  sample_.input_speed_rad_s =
      units_.speed(static_cast<double>(drive_velocity_layout_.signed_value(frame, 0)));
  sample_.flags |= storage::kInputSpeedValid;
  if (drive_velocity_layout_.size() > 1) {
    drive_.following_error_rad =
        units_.angle(static_cast<double>(drive_velocity_layout_.signed_value(frame, 1)));
    drive_.following_error_valid = true;
  }
  return true;
}

bool SampleAssembler::on_encoder(const can::Frame& frame) {
  if (frame.len < 4 || !take(kEncoder)) return false;
  const std::uint32_t raw = frame.data[0] | frame.data[1] << 8 | frame.data[2] << 16 |
                            static_cast<std::uint32_t>(frame.data[3]) << 24;
  // A CiA 406 position value is the count whose interval holds the angle (truncated): its
  // centre, half a count up, is the unbiased angle.
  sample_.theta_out_rad = encoder_.on_position(raw) +
                          std::numbers::pi / static_cast<double>(encoder_.counts_per_turn());
  sample_.flags |= storage::kThetaOutValid;
  return true;
}

bool SampleAssembler::on_torque(const can::Frame& frame) {
  if (!torque_layout_.fits(frame) || !take(kTorque)) return false;
  sample_.torque_nm = torque_.torque_from_raw(torque_layout_.raw(frame, 0));
  sample_.flags |= storage::kTorqueValid;
  return true;
}

bool SampleAssembler::on_extra(std::size_t i, std::optional<double> value) {
  if (!open_ || i >= storage::kMaxExtraChannels || (extra_expected_ >> i & 1U) == 0 ||
      (extra_arrived_ >> i & 1U) != 0 || !value)
    return false;
  extra_arrived_ |= 1U << i;
  sample_.extra[i] = *value;
  sample_.extra_valid |= 1U << i;
  return true;
}

void SampleAssembler::set_brake(double current_a, double torque_nm) {
  sample_.brake_current_a = current_a;
  sample_.brake_torque_nm = torque_nm;
  sample_.flags |= storage::kBrakeCurrentValid | storage::kBrakeTorqueValid;
}

const storage::SyncSample& SampleAssembler::finish() {
  open_ = false;
  return sample_;
}

}  // namespace wavebench::bench
