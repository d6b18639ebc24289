#include "wavebench/simdevices/output_encoder.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wavebench::simdevices {
namespace {

NodeIdentity with_device_type(NodeIdentity id, const EncoderConfig& c) {
  // CiA 406 device type: profile 0x0196, additional information 1 = single-turn, 2 = multi-turn.
  id.device_type = c.revolutions > 1 ? 0x00020196U : 0x00010196U;
  return id;
}

}  // namespace

Cia406Encoder::Cia406Encoder(const EncoderConfig& config, FrameSink sink)
    : CanopenNode(config.node_id, with_device_type(config.identity, config), std::move(sink)),
      config_(config),
      rng_(config.seed) {
  const std::uint64_t total =
      static_cast<std::uint64_t>(config.single_turn_resolution) * config.revolutions;
  if (config.single_turn_resolution == 0 || config.revolutions == 0 || total > (1ULL << 32)) {
    throw std::invalid_argument(
        "encoder: single_turn_resolution " + std::to_string(config.single_turn_resolution) +
        " x revolutions " + std::to_string(config.revolutions) +
        " is not a usable measuring range (expected both > 0 and a product <= 2^32)");
  }
  auto& d = od();
  using DT = DataType;
  using A = Access;
  auto& op = d.add_value<std::uint16_t>(0x6000, 0, "operating parameters", DT::kUnsigned16,
                                        A::kReadWrite, 0);
  op.max = 0x0001;  // bit 0: code sequence (1 = counting down); no scaling support
  d.add_value<std::uint32_t>(0x6001, 0, "measuring units per revolution", DT::kUnsigned32,
                             A::kReadOnly, config.single_turn_resolution);
  d.add_value<std::uint32_t>(0x6002, 0, "total measuring range", DT::kUnsigned32, A::kReadOnly,
                             static_cast<std::uint32_t>(total - 1 == 0xFFFFFFFFULL ? 0 : total));
  d.add_value<std::uint32_t>(0x6003, 0, "preset value", DT::kUnsigned32, A::kReadWrite, 0)
      .after_write = [this] {
    const auto preset = static_cast<std::int64_t>(od().get<std::uint32_t>(0x6003, 0));
    preset_offset_ = preset - raw_counts(angle_);
    observe(angle_);
  };
  d.add_value<std::uint32_t>(0x6004, 0, "position value", DT::kUnsigned32, A::kReadOnly, 0, true);
  d.add_value<std::uint16_t>(0x6500, 0, "operating status", DT::kUnsigned16, A::kReadOnly, 0);
  d.add_value<std::uint32_t>(0x6501, 0, "single-turn resolution", DT::kUnsigned32, A::kReadOnly,
                             config.single_turn_resolution);
  d.add_value<std::uint16_t>(0x6502, 0, "number of distinguishable revolutions", DT::kUnsigned16,
                             A::kReadOnly, config.revolutions);
  d.add_value<std::uint16_t>(0x6503, 0, "alarms", DT::kUnsigned16, A::kReadOnly, 0, true);
  d.add_value<std::uint16_t>(0x6504, 0, "supported alarms", DT::kUnsigned16, A::kReadOnly, 0);
  d.add_value<std::uint16_t>(0x6505, 0, "warnings", DT::kUnsigned16, A::kReadOnly, 0, true);
  d.add_value<std::uint16_t>(0x6506, 0, "supported warnings", DT::kUnsigned16, A::kReadOnly, 0);
  set_default_tpdo(1, {{0x6004, 0, 32}}, true, 1);
  for (const auto& fixed : config.fixed_tpdos) fix_tpdo(fixed);
  observe(0);
}

void Cia406Encoder::on_reset_application() {
  preset_offset_ = 0;
  observe(angle_);
}

std::int64_t Cia406Encoder::raw_counts(double angle_rad) const {
  const bool down = od().get<std::uint16_t>(0x6000, 0) & 0x0001;
  const double turns = (down ? -angle_rad : angle_rad) / (2 * std::numbers::pi);
  return static_cast<std::int64_t>(std::floor(turns * config_.single_turn_resolution));
}

void Cia406Encoder::observe(double angle_rad) {
  angle_ = angle_rad;
  const double noisy = angle_rad + config_.noise_rad * noise_(rng_);
  const auto total =
      static_cast<std::int64_t>(config_.single_turn_resolution) * config_.revolutions;
  std::int64_t counts = (raw_counts(noisy) + preset_offset_) % total;
  if (counts < 0) counts += total;
  od().set<std::uint32_t>(0x6004, 0, static_cast<std::uint32_t>(counts));
  if (config_.revolutions > 1) {
    od().set<std::uint16_t>(0x6500, 0,
                            static_cast<std::uint16_t>(od().get<std::uint16_t>(0x6000, 0)));
  }
}

}  // namespace wavebench::simdevices
