// A CiA 406 rotary encoder as a bench device: one angle channel [rad] from 0x6004 in TPDO1,
// unwrapped across the encoder's own wrap, at the centre of the count that holds it (a CiA 406
// position value is the count whose interval holds the angle, truncated: half a count up is the
// unbiased angle). The output encoder is one; seed 004's input-side encoder is another.
#include <numbers>

#include "device_kinds.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"

namespace wavebench::bench {
namespace {

const canopen::NeededObject kNeeded[] = {{0x6004, 0, 32, "position value"}};

class Cia406EncoderDevice final : public CanopenDevice {
 public:
  Cia406EncoderDevice(std::string name, const ChannelDeviceSettings& s)
      : CanopenDevice(std::move(name), s.node), settings_(s) {}

  std::vector<storage::ChannelInfo> channels() const override {
    return {{settings_.channel, "rad"}};
  }
  std::uint16_t profile() const noexcept override { return 0x0196; }
  std::vector<canopen::UsedObject> used_objects() const override {
    const auto used = canopen::Cia406Encoder::used_objects();
    return {used.begin(), used.end()};
  }

  void configure(canopen::SdoClient& sdo) override {
    encoder_.reset();
    auto encoder = std::make_unique<canopen::Cia406Encoder>(
        sdo, canopen::Cia406Config{settings_.counts_per_turn, settings_.turns});
    encoder->read_configuration();
    adopted_ = {};
    adopt_tpdos(sdo, {bench_tpdo()}, kNeeded);
    encoder_ = std::move(encoder);
  }

  std::vector<canopen::PdoConfig> tpdos() const override {
    if (!adopted_.pdos().empty()) return adopted_.configs();
    return {bench_tpdo()};
  }

  bool on_pdo(std::size_t i, const can::Frame& frame, CycleRecord& record) noexcept override {
    if (!encoder_) return false;
    // 0x6004 wherever the device maps it (a fixed mapping may put it at a bit offset).
    const auto position = adopted_.raw(0, i, frame);
    if (!position) return false;
    const auto raw = static_cast<std::uint32_t>(*position);
    const double angle = encoder_->on_position(raw) +
                         std::numbers::pi / static_cast<double>(encoder_->counts_per_turn());
    put(record, 0, settings_.sign * angle);
    return true;
  }

 private:
  canopen::PdoConfig bench_tpdo() const {
    return {canopen::tpdo_cob_id(1, node()), 1, 0, {{0x6004, 0, 32}}};
  }

  ChannelDeviceSettings settings_;
  std::unique_ptr<canopen::Cia406Encoder> encoder_;
};

}  // namespace

ChannelDeviceKind cia406_encoder_kind() {
  return {"cia406_encoder",
          "a CiA 406 rotary encoder; its angle [rad] from 0x6004 in TPDO1",
          {"counts_per_turn", "turns"},
          [](std::string name, const ChannelDeviceSettings& s) -> std::unique_ptr<CanopenDevice> {
            return std::make_unique<Cia406EncoderDevice>(std::move(name), s);
          }};
}

}  // namespace wavebench::bench
