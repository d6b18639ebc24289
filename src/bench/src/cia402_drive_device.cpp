#include "wavebench/bench/cia402_drive_device.hpp"

#include "wavebench/bench/quick_stop_watch.hpp"

namespace wavebench::bench {
namespace {

const std::vector<canopen::PdoEntry> kPositionMapping{{0x6041, 0, 16}, {0x6064, 0, 32}};

std::vector<canopen::PdoEntry> velocity_mapping(bool following_error) {
  if (following_error) return {{0x606C, 0, 32}, {0x60F4, 0, 32}};
  return {{0x606C, 0, 32}};
}

// What the bench needs from the drive's TPDOs, wherever the drive maps it (the index into this
// list is the one AdoptedTpdos::raw takes).
enum Needed : std::size_t { kStatusword, kPosition, kVelocity, kFollowingError };
const canopen::NeededObject kNeeded[] = {
    {0x6041, 0, 16, "statusword"},
    {0x6064, 0, 32, "position actual value"},
    {0x606C, 0, 32, "velocity actual value"},
    {0x60F4, 0, 32, "following error actual value", true},
};

}  // namespace

Cia402DriveDevice::Cia402DriveDevice(canopen::NodeId node, DriveSettings settings)
    : CanopenDevice("servo drive", node), settings_(std::move(settings)) {}

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
  adopted_ = {};
  channels_ = read_drive_channels(sdo, settings_);
  std::vector<canopen::PdoAdoption> candidates;
  candidates.push_back(
      canopen::configure_or_read_back(sdo, PdoDirection::transmit, 1, position_pdo(node())));
  candidates.push_back(map_drive_velocity_pdo(sdo, channels_));
  adopted_ = canopen::use_tpdos(sdo, std::move(candidates), kNeeded);
  if (channels_.following_error && !adopted_.has(kFollowingError)) {
    channels_.following_error = false;
    channels_.absent.push_back({kFollowingErrorChannel,
                                "0x60F4 (following error actual value) is not in the drive's "
                                "fixed TPDOs (" +
                                    adopted_.summary() + ")"});
  }
  try {
    canopen::configure_pdo(sdo, PdoDirection::receive, kQuickStopRpdo, quick_stop_rpdo(node()));
  } catch (const std::system_error& e) {
    // Not adopted as found: the quick stop's frame is the bench's own (quick_stop_watch.hpp).
    throw std::runtime_error(std::string(e.what()) + ": the quick stop needs RPDO" +
                             std::to_string(kQuickStopRpdo) +
                             " mapped with the controlword 0x6040 alone; a fixed RPDO is not used");
  }
  // 0x6007 is optional (CiA 402): where present, an NMT stop (the quick stop's fallback)
  // disables the drive's voltage.
  std::error_code ec;
  sdo.write<std::int16_t>(0x6007, 0, kAbortConnectionDisableVoltage, ec);
  abort_option_set_ = !ec;
  position_ = Int32Unwrapper{};
  drive_ = std::make_unique<canopen::Cia402Drive>(sdo);
}

std::vector<canopen::PdoConfig> Cia402DriveDevice::tpdos() const {
  if (!adopted_.pdos().empty()) return adopted_.configs();
  return {position_pdo(node()), velocity_pdo(node(), channels_.following_error)};
}

bool Cia402DriveDevice::on_pdo(std::size_t i, const can::Frame& frame,
                               CycleRecord& record) noexcept {
  // Each value from whichever TPDO carries it (a fixed mapping: as the drive has it).
  if (!adopted_.fits(i, frame)) return false;
  if (const auto sw = adopted_.raw(kStatusword, i, frame)) {
    record.drive.statusword = static_cast<std::uint16_t>(*sw);
    record.drive.status_valid = true;
  }
  if (const auto raw = adopted_.signed_value(kPosition, i, frame)) {
    put(record, 0,
        channels_.units.angle(
            static_cast<double>(position_.update(static_cast<std::int32_t>(*raw)))));
  }
  if (const auto raw = adopted_.signed_value(kVelocity, i, frame))
    put(record, 1, channels_.units.speed(static_cast<double>(*raw)));
  if (channels_.following_error) {
    if (const auto raw = adopted_.signed_value(kFollowingError, i, frame)) {
      record.drive.following_error_rad = channels_.units.angle(static_cast<double>(*raw));
      record.drive.following_error_valid = true;
    }
  }
  return true;
}

}  // namespace wavebench::bench
