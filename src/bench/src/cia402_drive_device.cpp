#include "wavebench/bench/cia402_drive_device.hpp"

#include "wavebench/bench/quick_stop_watch.hpp"

namespace wavebench::bench {
namespace {

const std::vector<canopen::PdoEntry> kPositionMapping{{0x6041, 0, 16}, {0x6064, 0, 32}};

std::vector<canopen::PdoEntry> velocity_mapping(bool following_error) {
  if (following_error) return {{0x606C, 0, 32}, {0x60F4, 0, 32}};
  return {{0x606C, 0, 32}};
}

}  // namespace

Cia402DriveDevice::Cia402DriveDevice(canopen::NodeId node, DriveSettings settings)
    : CanopenDevice("servo drive", node),
      settings_(std::move(settings)),
      position_layout_(kPositionMapping),
      velocity_layout_(velocity_mapping(true)) {}

canopen::PdoConfig Cia402DriveDevice::position_pdo(canopen::NodeId node) {
  return {canopen::tpdo_cob_id(1, node), 1, 0, kPositionMapping};
}

canopen::PdoConfig Cia402DriveDevice::velocity_pdo(canopen::NodeId node, bool following_error) {
  return {canopen::tpdo_cob_id(2, node), 1, 0, velocity_mapping(following_error)};
}

std::vector<storage::ChannelInfo> Cia402DriveDevice::channels() const {
  return {{"theta_in", "rad"}, {"input_speed", "rad/s"}};
}

std::vector<CommandInterface> Cia402DriveDevice::commands() const {
  return {{"input_position", "rad"}, {"input_velocity", "rad/s"}};
}

std::vector<canopen::UsedObject> Cia402DriveDevice::used_objects() const {
  const auto used = canopen::Cia402Drive::used_objects();
  return {used.begin(), used.end()};
}

void Cia402DriveDevice::configure(canopen::SdoClient& sdo) {
  using canopen::PdoDirection;
  drive_.reset();
  channels_ = read_drive_channels(sdo, settings_);
  canopen::configure_pdo(sdo, PdoDirection::transmit, 1, position_pdo(node()));
  map_drive_velocity_pdo(sdo, channels_);
  velocity_layout_ = canopen::PdoLayout(velocity_mapping(channels_.following_error));
  canopen::configure_pdo(sdo, PdoDirection::receive, kQuickStopRpdo, quick_stop_rpdo(node()));
  // 0x6007 is optional (CiA 402): where present, an NMT stop (the quick stop's fallback)
  // disables the drive's voltage.
  std::error_code ec;
  sdo.write<std::int16_t>(0x6007, 0, kAbortConnectionDisableVoltage, ec);
  abort_option_set_ = !ec;
  position_ = Int32Unwrapper{};
  drive_ = std::make_unique<canopen::Cia402Drive>(sdo);
}

std::vector<canopen::PdoConfig> Cia402DriveDevice::tpdos() const {
  return {position_pdo(node()), velocity_pdo(node(), channels_.following_error)};
}

bool Cia402DriveDevice::on_pdo(std::size_t i, const can::Frame& frame,
                               CycleRecord& record) noexcept {
  if (i == 0) {
    if (!position_layout_.fits(frame)) return false;
    record.drive.statusword = static_cast<std::uint16_t>(position_layout_.raw(frame, 0));
    record.drive.status_valid = true;
    const auto raw = static_cast<std::int32_t>(position_layout_.signed_value(frame, 1));
    put(record, 0, channels_.units.angle(static_cast<double>(position_.update(raw))));
    return true;
  }
  if (i == 1) {
    if (!velocity_layout_.fits(frame)) return false;
    put(record, 1,
        channels_.units.speed(static_cast<double>(velocity_layout_.signed_value(frame, 0))));
    if (velocity_layout_.size() > 1) {
      record.drive.following_error_rad =
          channels_.units.angle(static_cast<double>(velocity_layout_.signed_value(frame, 1)));
      record.drive.following_error_valid = true;
    }
    return true;
  }
  return false;
}

}  // namespace wavebench::bench
