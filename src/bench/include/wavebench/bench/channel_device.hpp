#pragma once
// A CANopen device the bench records beside the drive, the output encoder and the torque
// sensor: an input-side CiA 406 encoder (seed 004's bench), a second torque sensor. One driver
// object per node, after lely-core's per-node drivers: it configures its node (reads what it
// needs, maps its TPDO) and is called on boot, heartbeat and EMCY; and after ros2_control's
// state interfaces it exports one named channel, which lands in SyncSample::extra and the
// sample log. A bench config lists these under `devices:`; a new kind of device is one file
// and one line in channel_device_registry.cpp.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/storage/channel_info.hpp"

namespace wavebench::bench {

// One entry of the bench config's `devices:` (see configs/benches/README.md).
struct ChannelDeviceSettings {
  std::string channel;  // the key under devices: and the channel's name
  std::string kind;     // a key of the registry: cia406_encoder, torque_sensor
  std::uint8_t node = 0;
  int sign = 1;  // -1: the device counts against the bench's positive direction
  // cia406_encoder: unset reads 0x6501 / 0x6502.
  std::optional<std::uint32_t> counts_per_turn;
  std::optional<std::uint32_t> turns;
  // torque_sensor: the object, type, scale and offset of its torque.
  canopen::TorqueSensorConfig torque{0x6130, 1, canopen::ValueType::i32, 1e-3, 0.0};
};

class ChannelDevice {
 public:
  explicit ChannelDevice(ChannelDeviceSettings settings) : settings_(std::move(settings)) {}
  virtual ~ChannelDevice() = default;
  ChannelDevice(const ChannelDevice&) = delete;
  ChannelDevice& operator=(const ChannelDevice&) = delete;

  const ChannelDeviceSettings& settings() const noexcept { return settings_; }
  std::uint8_t node() const noexcept { return settings_.node; }
  // For messages: "input encoder 'theta_in_encoder' (node 5)".
  std::string describe() const;

  virtual storage::ChannelInfo channel() const = 0;
  // Configuration hook, by SDO while the node is pre-operational: reads what the device needs.
  // Throws naming the object.
  virtual void configure(canopen::SdoClient& sdo) = 0;
  // The synchronous TPDO the bench maps on the node (TPDO1, every SYNC).
  virtual canopen::PdoConfig tpdo() const = 0;
  // Its TPDO of the open cycle: the channel's value [SI], or nullopt when the frame does not
  // match the mapping.
  virtual std::optional<double> on_pdo(const can::Frame& frame) noexcept = 0;
  // Hooks of the node's life; the bench trips on EMCY and a lost heartbeat itself.
  virtual void on_boot() noexcept {}
  virtual void on_heartbeat(std::uint8_t nmt_state) noexcept { (void)nmt_state; }
  virtual void on_emcy(const canopen::Emergency& emcy) noexcept { (void)emcy; }

 private:
  ChannelDeviceSettings settings_;
};

struct ChannelDeviceKind {
  std::string kind;
  std::string description;
  // The keys its settings may have beside kind, node and sign (for the config's key check).
  std::vector<std::string> keys;
  std::function<std::unique_ptr<ChannelDevice>(const ChannelDeviceSettings&)> make;
};

// Every kind of channel device, by name.
const std::vector<ChannelDeviceKind>& channel_device_kinds();
const ChannelDeviceKind* find_channel_device_kind(const std::string& kind);

}  // namespace wavebench::bench
