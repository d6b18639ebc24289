#include "wavebench/modbus/register_codec.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::modbus {

int register_count(DataType type) {
  switch (type) {
    case DataType::uint16:
    case DataType::int16:
      return 1;
    case DataType::uint32:
    case DataType::int32:
    case DataType::float32:
      return 2;
  }
  return 1;
}

std::string to_string(RegisterTable table) {
  return table == RegisterTable::holding ? "holding" : "input";
}

std::string to_string(DataType type) {
  switch (type) {
    case DataType::uint16:
      return "uint16";
    case DataType::int16:
      return "int16";
    case DataType::uint32:
      return "uint32";
    case DataType::int32:
      return "int32";
    case DataType::float32:
      return "float32";
  }
  return "?";
}

std::string to_string(WordOrder order) {
  switch (order) {
    case WordOrder::abcd:
      return "abcd";
    case WordOrder::cdab:
      return "cdab";
    case WordOrder::badc:
      return "badc";
    case WordOrder::dcba:
      return "dcba";
  }
  return "?";
}

namespace {
uint16_t swap_bytes(uint16_t w) {
  return static_cast<uint16_t>((w >> 8) | (w << 8));
}
}  // namespace

void split_u32(uint32_t bits, WordOrder order, uint16_t* regs) {
  const auto hi = static_cast<uint16_t>(bits >> 16);      // bytes A B
  const auto lo = static_cast<uint16_t>(bits & 0xFFFFu);  // bytes C D
  switch (order) {
    case WordOrder::abcd:
      regs[0] = hi;
      regs[1] = lo;
      break;
    case WordOrder::cdab:
      regs[0] = lo;
      regs[1] = hi;
      break;
    case WordOrder::badc:
      regs[0] = swap_bytes(hi);
      regs[1] = swap_bytes(lo);
      break;
    case WordOrder::dcba:
      regs[0] = swap_bytes(lo);
      regs[1] = swap_bytes(hi);
      break;
  }
}

uint32_t join_u32(const uint16_t* regs, WordOrder order) {
  uint16_t hi = 0;
  uint16_t lo = 0;
  switch (order) {
    case WordOrder::abcd:
      hi = regs[0];
      lo = regs[1];
      break;
    case WordOrder::cdab:
      lo = regs[0];
      hi = regs[1];
      break;
    case WordOrder::badc:
      hi = swap_bytes(regs[0]);
      lo = swap_bytes(regs[1]);
      break;
    case WordOrder::dcba:
      lo = swap_bytes(regs[0]);
      hi = swap_bytes(regs[1]);
      break;
  }
  return (static_cast<uint32_t>(hi) << 16) | lo;
}

double decode_value(const RegisterSpec& spec, WordOrder order, const uint16_t* regs) {
  double raw = 0.0;
  switch (spec.type) {
    case DataType::uint16:
      raw = regs[0];
      break;
    case DataType::int16:
      raw = static_cast<int16_t>(regs[0]);
      break;
    case DataType::uint32:
      raw = join_u32(regs, order);
      break;
    case DataType::int32:
      raw = static_cast<int32_t>(join_u32(regs, order));
      break;
    case DataType::float32:
      raw = static_cast<double>(std::bit_cast<float>(join_u32(regs, order)));
      break;
  }
  return raw * spec.scale + spec.offset;
}

namespace {
template <typename T>
T to_integer(double raw, double value, const RegisterSpec& spec) {
  const double rounded = std::round(raw);
  if (!std::isfinite(rounded) || rounded < static_cast<double>(std::numeric_limits<T>::min()) ||
      rounded > static_cast<double>(std::numeric_limits<T>::max())) {
    throw std::out_of_range("value " + std::to_string(value) + " does not fit register " +
                            std::to_string(spec.address) + " (" + to_string(spec.type) +
                            ", scale " + std::to_string(spec.scale) + ")");
  }
  return static_cast<T>(rounded);
}
}  // namespace

std::vector<uint16_t> encode_value(const RegisterSpec& spec, WordOrder order, double value) {
  const double raw = (value - spec.offset) / spec.scale;
  std::vector<uint16_t> regs(static_cast<size_t>(register_count(spec.type)));
  switch (spec.type) {
    case DataType::uint16:
      regs[0] = to_integer<uint16_t>(raw, value, spec);
      break;
    case DataType::int16:
      regs[0] = static_cast<uint16_t>(to_integer<int16_t>(raw, value, spec));
      break;
    case DataType::uint32:
      split_u32(to_integer<uint32_t>(raw, value, spec), order, regs.data());
      break;
    case DataType::int32:
      split_u32(static_cast<uint32_t>(to_integer<int32_t>(raw, value, spec)), order, regs.data());
      break;
    case DataType::float32:
      if (!std::isfinite(raw)) {
        throw std::out_of_range("value " + std::to_string(value) + " is not a finite number");
      }
      split_u32(std::bit_cast<uint32_t>(static_cast<float>(raw)), order, regs.data());
      break;
  }
  return regs;
}

}  // namespace wavebench::modbus
