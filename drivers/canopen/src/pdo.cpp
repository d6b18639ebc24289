#include "wavebench/canopen/pdo.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {

namespace {

struct PdoObjects {
  std::uint16_t communication;
  std::uint16_t mapping;
};

PdoObjects objects(PdoDirection direction, unsigned number) {
  if (number < 1 || number > 512) {
    throw std::invalid_argument("PDO number " + std::to_string(number) + ": expected 1..512");
  }
  const auto n = static_cast<std::uint16_t>(number - 1);
  if (direction == PdoDirection::transmit) {
    return {static_cast<std::uint16_t>(0x1800 + n), static_cast<std::uint16_t>(0x1A00 + n)};
  }
  return {static_cast<std::uint16_t>(0x1400 + n), static_cast<std::uint16_t>(0x1600 + n)};
}

}  // namespace

void configure_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, const PdoConfig& config,
                   std::error_code& ec) noexcept {
  ec.clear();
  if (number < 1 || number > 512 || config.entries.size() > 64) {
    ec = make_error_code(SdoAbort::invalid_value);
    return;
  }
  const auto obj = objects(direction, number);
  const std::uint32_t cob = config.cob_id & ~kCobIdInvalid;
  sdo.write<std::uint32_t>(obj.communication, 1, cob | kCobIdInvalid, ec);
  if (ec) return;
  sdo.write<std::uint8_t>(obj.communication, 2, config.transmission_type, ec);
  if (ec) return;
  if (config.event_timer_ms != 0) {
    sdo.write<std::uint16_t>(obj.communication, 5, config.event_timer_ms, ec);
    if (ec) return;
  }
  sdo.write<std::uint8_t>(obj.mapping, 0, 0, ec);
  if (ec) return;
  std::uint8_t sub = 1;
  for (const auto& entry : config.entries) {
    sdo.write<std::uint32_t>(obj.mapping, sub++, entry.encode(), ec);
    if (ec) return;
  }
  sdo.write<std::uint8_t>(obj.mapping, 0, static_cast<std::uint8_t>(config.entries.size()), ec);
  if (ec) return;
  sdo.write<std::uint32_t>(obj.communication, 1, cob, ec);
}

void configure_pdo(SdoClient& sdo, PdoDirection direction, unsigned number,
                   const PdoConfig& config) {
  std::error_code ec;
  configure_pdo(sdo, direction, number, config, ec);
  if (ec) {
    throw std::system_error(ec, std::string(direction == PdoDirection::transmit ? "TPDO" : "RPDO") +
                                    std::to_string(number) + " of node " +
                                    std::to_string(sdo.node()) + " configuration");
  }
}

void disable_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, std::uint32_t cob_id,
                 std::error_code& ec) noexcept {
  if (number < 1 || number > 512) {
    ec = make_error_code(SdoAbort::invalid_value);
    return;
  }
  sdo.write<std::uint32_t>(objects(direction, number).communication, 1, cob_id | kCobIdInvalid, ec);
}

std::uint64_t extract_bits(std::span<const std::uint8_t> data, unsigned offset,
                           unsigned bits) noexcept {
  std::uint64_t value = 0;
  for (unsigned b = 0; b < bits; ++b) {
    const unsigned pos = offset + b;
    if (pos / 8 >= data.size()) break;
    if ((data[pos / 8] >> (pos % 8)) & 1U) value |= std::uint64_t{1} << b;
  }
  return value;
}

void insert_bits(std::span<std::uint8_t> data, unsigned offset, unsigned bits,
                 std::uint64_t value) noexcept {
  for (unsigned b = 0; b < bits; ++b) {
    const unsigned pos = offset + b;
    if (pos / 8 >= data.size()) break;
    const auto mask = static_cast<std::uint8_t>(1U << (pos % 8));
    if ((value >> b) & 1U) {
      data[pos / 8] |= mask;
    } else {
      data[pos / 8] &= static_cast<std::uint8_t>(~mask);
    }
  }
}

PdoLayout::PdoLayout(std::vector<PdoEntry> entries) : entries_(std::move(entries)) {
  for (const auto& e : entries_) {
    if (e.bits == 0 || e.bits > 64) {
      throw std::invalid_argument("PDO entry " + std::to_string(e.index) + ":" +
                                  std::to_string(e.sub) + " length " + std::to_string(e.bits) +
                                  " bits: expected 1..64");
    }
    offsets_.push_back(total_bits_);
    total_bits_ += e.bits;
  }
  if (total_bits_ > 64) {
    throw std::invalid_argument("PDO mapping of " + std::to_string(total_bits_) +
                                " bits: expected at most 64 (8 bytes)");
  }
}

std::uint64_t PdoLayout::raw(const can::Frame& frame, std::size_t i) const noexcept {
  if (i >= entries_.size()) return 0;
  return extract_bits(frame.payload(), offsets_[i], entries_[i].bits);
}

std::int64_t PdoLayout::signed_value(const can::Frame& frame, std::size_t i) const noexcept {
  if (i >= entries_.size()) return 0;
  const unsigned bits = entries_[i].bits;
  std::uint64_t v = raw(frame, i);
  if (bits < 64 && ((v >> (bits - 1)) & 1U)) v |= ~std::uint64_t{0} << bits;
  return static_cast<std::int64_t>(v);
}

float PdoLayout::f32(const can::Frame& frame, std::size_t i) const noexcept {
  return std::bit_cast<float>(static_cast<std::uint32_t>(raw(frame, i)));
}

double PdoLayout::f64(const can::Frame& frame, std::size_t i) const noexcept {
  return std::bit_cast<double>(raw(frame, i));
}

void PdoLayout::set_raw(can::Frame& frame, std::size_t i, std::uint64_t value) const noexcept {
  if (i >= entries_.size()) return;
  insert_bits(std::span<std::uint8_t>(frame.data.data(), frame.data.size()), offsets_[i],
              entries_[i].bits, value);
}

can::Frame PdoLayout::make_frame(std::uint32_t cob_id,
                                 std::span<const std::uint64_t> raw_values) const {
  if (raw_values.size() != entries_.size()) {
    throw std::invalid_argument("PDO frame with " + std::to_string(raw_values.size()) +
                                " values: expected " + std::to_string(entries_.size()));
  }
  can::Frame f;
  f.id = cob_id & can::kStandardIdMask;
  f.len = static_cast<std::uint8_t>(length_bytes());
  for (std::size_t i = 0; i < raw_values.size(); ++i) set_raw(f, i, raw_values[i]);
  return f;
}

}  // namespace wavebench::canopen
