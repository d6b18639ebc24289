#pragma once
// A device of the bench, one driver object per device (after lely-core's per-node drivers): it
// configures itself, is called on the hooks of its life, and exports named state interfaces
// (the channels it writes into each cycle's sample) and command interfaces (the set-points it
// takes), after ros2_control's hardware interfaces. The cycle engine (cycle_engine.hpp) feeds
// the CANopen ones their TPDOs; the bench (canopen_bench.hpp) drives their commands.
//
// Where a new device goes: a CANopen node that records channels is a CanopenDevice, made from
// the bench config's `devices:` by the registry in device_kind_registry.cpp (one file per kind).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "wavebench/bench/bench_lifecycle.hpp"
#include "wavebench/bench/cycle_record.hpp"
#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/pdo_adoption.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/used_object.hpp"
#include "wavebench/storage/channel_info.hpp"

namespace wavebench::bench {

// A set-point a device takes, by name and SI unit (e.g. "input_velocity" [rad/s]).
struct CommandInterface {
  std::string name;
  std::string unit;
};

class BenchDevice {
 public:
  explicit BenchDevice(std::string name) : name_(std::move(name)) {}
  virtual ~BenchDevice() = default;
  BenchDevice(const BenchDevice&) = delete;
  BenchDevice& operator=(const BenchDevice&) = delete;

  // For messages: "servo drive", "cia406_encoder 'theta_in_encoder'".
  const std::string& name() const noexcept { return name_; }
  virtual std::string describe() const { return name_; }

  // State interfaces: the channels it writes, each at the slot bind() gave it.
  virtual std::vector<storage::ChannelInfo> channels() const = 0;
  virtual std::vector<CommandInterface> commands() const { return {}; }
  // The slot of each of channels(), in the same order (the bench's channel table decides).
  void bind(std::vector<ChannelSlot> slots) { slots_ = std::move(slots); }
  const std::vector<ChannelSlot>& slots() const noexcept { return slots_; }

  // State-change hook: the bench's lifecycle moved to `state`.
  virtual void on_state_change(BenchLifecycle state) noexcept { (void)state; }
  // End of a cycle, before the sample goes to observers: a device not on the SYNC (the Modbus
  // brake) writes its latest fresh values here.
  virtual void on_cycle_end(CycleRecord& record) noexcept { (void)record; }

 protected:
  // Writes channel `i` of channels() into the record at its slot.
  void put(CycleRecord& record, std::size_t i, double value) const noexcept {
    if (i < slots_.size()) record.set(slots_[i], value);
  }

 private:
  std::string name_;
  std::vector<ChannelSlot> slots_;
};

// A CANopen node of the bench: configured by SDO while pre-operational, then its synchronous
// TPDOs arrive after every SYNC.
class CanopenDevice : public BenchDevice {
 public:
  CanopenDevice(std::string name, canopen::NodeId node)
      : BenchDevice(std::move(name)), node_(node) {}

  canopen::NodeId node() const noexcept { return node_; }
  std::string describe() const override { return name() + " (node " + std::to_string(node_) + ")"; }
  // CiA device profile expected in 0x1000's low word (0x0192 drive, 0x0196 encoder), 0: any.
  virtual std::uint16_t profile() const noexcept { return 0; }
  // Every object the bench uses on the node (checked against its EDS and by the commissioning
  // check).
  virtual std::vector<canopen::UsedObject> used_objects() const = 0;

  // Configuration hook, by SDO while the node is pre-operational: reads what the device needs
  // and maps its PDOs. Throws naming the object.
  virtual void configure(canopen::SdoClient& sdo) = 0;
  // The synchronous TPDOs the bench maps on the node; after configure(): as the device uses
  // them, which for a mapping the device would not let the bench write is as found.
  virtual std::vector<canopen::PdoConfig> tpdos() const = 0;
  // After configure(): the TPDOs used, each with its PDO number and whether it was used as
  // found (fixed); empty before, or for a device that does not record it.
  const canopen::AdoptedTpdos& adopted_tpdos() const noexcept { return adopted_; }

  // SYNC hook: cycle `index` opened.
  virtual void on_sync(std::uint64_t index) noexcept { (void)index; }
  // TPDO `i` of tpdos() in the open cycle: writes its channels into the record; false when the
  // frame does not match the mapping.
  virtual bool on_pdo(std::size_t i, const can::Frame& frame, CycleRecord& record) noexcept = 0;
  virtual void on_boot() noexcept {}
  virtual void on_heartbeat(canopen::NmtState state) noexcept { (void)state; }
  virtual void on_emcy(const canopen::Emergency& emcy) noexcept { (void)emcy; }

 protected:
  // Maps the device's TPDOs, each the bench's mapping where the device takes it and the
  // device's own where it does not, and finds `needed` in them (canopen::use_tpdos; throws
  // naming what is missing). tpdos() is then adopted_tpdos().configs().
  void adopt_tpdos(canopen::SdoClient& sdo, const std::vector<canopen::PdoConfig>& wanted,
                   std::span<const canopen::NeededObject> needed);
  canopen::AdoptedTpdos adopted_;

 private:
  canopen::NodeId node_;
};

}  // namespace wavebench::bench
