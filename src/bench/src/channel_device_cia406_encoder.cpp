// A CiA 406 encoder as a channel device: an angle [rad], unwrapped across the encoder's own
// wrap, at the centre of the count that holds it (as the output encoder in the sample
// assembler).
#include <numbers>

#include "channel_device_kinds.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::bench {
namespace {

class Cia406ChannelDevice final : public ChannelDevice {
 public:
  using ChannelDevice::ChannelDevice;

  storage::ChannelInfo channel() const override { return {settings().channel, "rad"}; }

  void configure(canopen::SdoClient& sdo) override {
    encoder_ = std::make_unique<canopen::Cia406Encoder>(
        sdo, canopen::Cia406Config{settings().counts_per_turn, settings().turns});
    encoder_->read_configuration();
  }

  canopen::PdoConfig tpdo() const override {
    return {canopen::tpdo_cob_id(1, node()), 1, 0, {{0x6004, 0, 32}}};
  }

  std::optional<double> on_pdo(const can::Frame& frame) noexcept override {
    if (!encoder_ || frame.len < 4) return std::nullopt;
    const std::uint32_t raw = frame.data[0] | frame.data[1] << 8 | frame.data[2] << 16 |
                              static_cast<std::uint32_t>(frame.data[3]) << 24;
    const double angle = encoder_->on_position(raw) +
                         std::numbers::pi / static_cast<double>(encoder_->counts_per_turn());
    return settings().sign * angle;
  }

 private:
  std::unique_ptr<canopen::Cia406Encoder> encoder_;
};

}  // namespace

ChannelDeviceKind cia406_encoder_kind() {
  return {"cia406_encoder",
          "a CiA 406 rotary encoder; its angle [rad] from 0x6004 in TPDO1",
          {"counts_per_turn", "turns"},
          [](const ChannelDeviceSettings& s) { return std::make_unique<Cia406ChannelDevice>(s); }};
}

}  // namespace wavebench::bench
