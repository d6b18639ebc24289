#include "wavebench/canopen/cia406_encoder.hpp"

#include <fmt/format.h>

#include <numbers>

namespace wavebench::canopen {

namespace {
using enum UsedAccess;
using enum UsedInPdo;
namespace dt = datatype;

constexpr auto kEncoderObjects = with_node_objects(std::to_array<UsedObject>({
    {0x6004, 0, "position value", dt::kUnsigned32, 0, kRead, kTpdo},
    {0x6501, 0, "single-turn resolution", dt::kUnsigned32, 0, kRead},
    // CiA 406 v3 says UNSIGNED16; some devices use UNSIGNED32 (read_configuration takes both).
    {0x6502, 0, "number of distinguishable revolutions", dt::kUnsigned16, dt::kUnsigned32, kRead,
     kNone, "a single-turn encoder: one turn (or encoder.turns)"},
    {0x6503, 0, "alarms", dt::kUnsigned16, 0, kRead, kNone, "the encoder's alarms are not read"},
}));

}  // namespace

std::span<const UsedObject> Cia406Encoder::used_objects() noexcept {
  return kEncoderObjects;
}

std::int64_t PositionUnwrapper::update(std::uint32_t raw) noexcept {
  const auto range = static_cast<std::int64_t>(range_);
  if (have_) {
    const std::int64_t step = static_cast<std::int64_t>(raw) - static_cast<std::int64_t>(last_);
    // A step of more than half the range is the encoder wrapping, not motion.
    if (step > range / 2) {
      --wraps_;
    } else if (step < -range / 2) {
      ++wraps_;
    }
  }
  have_ = true;
  last_ = raw;
  return wraps_ * range + static_cast<std::int64_t>(raw);
}

Cia406Encoder::Cia406Encoder(SdoClient& sdo, Cia406Config config) : sdo_(sdo), config_(config) {
  if (config_.counts_per_turn) counts_per_turn_ = *config_.counts_per_turn;
  if (config_.turns) turns_ = *config_.turns;
  if (config_.counts_per_turn && *config_.counts_per_turn == 0) {
    throw std::invalid_argument("encoder counts_per_turn 0: expected > 0");
  }
  if (config_.turns && *config_.turns == 0) {
    throw std::invalid_argument("encoder turns 0: expected >= 1");
  }
  unwrapper_ = PositionUnwrapper(std::uint64_t{counts_per_turn_} * turns_);
}

void Cia406Encoder::read_configuration(std::error_code& ec) noexcept {
  ec.clear();
  device_type_ = sdo_.read<std::uint32_t>(0x1000, 0, ec);
  if (ec) return;
  if (!config_.counts_per_turn) {
    counts_per_turn_ = sdo_.read<std::uint32_t>(0x6501, 0, ec);
    if (ec) return;
    if (counts_per_turn_ == 0) {
      ec = make_error_code(SdoAbort::invalid_value);
      return;
    }
  }
  if (!config_.turns) {
    if (multi_turn()) {
      // 0x6502 is UNSIGNED16 in CiA 406 v3; some devices use UNSIGNED32.
      const auto bytes = sdo_.upload(0x6502, 0, ec);
      if (ec) return;
      std::uint32_t v = 0;
      for (std::size_t i = 0; i < bytes.size() && i < 4; ++i)
        v |= std::uint32_t{bytes[i]} << (8 * i);
      turns_ = v == 0 ? 1 : v;
    } else {
      turns_ = 1;
    }
  }
  unwrapper_ = PositionUnwrapper(std::uint64_t{counts_per_turn_} * turns_);
}

void Cia406Encoder::read_configuration() {
  std::error_code ec;
  read_configuration(ec);
  if (ec) {
    throw std::system_error(
        ec, fmt::format("CiA 406 encoder node {}: reading 0x1000/0x6501/0x6502", sdo_.node()));
  }
}

double Cia406Encoder::on_position(std::uint32_t raw) noexcept {
  if (counts_per_turn_ == 0) return angle_;
  const auto counts = unwrapper_.update(raw);
  angle_ = static_cast<double>(counts) * 2.0 * std::numbers::pi / counts_per_turn_;
  return angle_;
}

double Cia406Encoder::read_angle() {
  return on_position(sdo_.read<std::uint32_t>(0x6004, 0));
}

std::uint16_t Cia406Encoder::read_alarms() {
  return sdo_.read<std::uint16_t>(0x6503, 0);
}

}  // namespace wavebench::canopen
