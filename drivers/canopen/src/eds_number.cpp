// CiA 306 numbers ($NODEID, hex, octal, decimal, sign) and whether a value fits its data type.
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "eds_detail.hpp"
#include "wavebench/canopen/eds.hpp"

namespace wavebench::canopen {
namespace {

using eds_detail::lower;
using eds_detail::trim;

// The sign apart from the magnitude, so that both INT64_MIN and UINT64_MAX read.
struct Number {
  bool negative = false;
  std::uint64_t magnitude = 0;
  bool node_id = false;  // $NODEID is to be added
};

Number parse_number(std::string_view text) {
  auto t = trim(text);
  if (t.empty()) throw std::invalid_argument("empty");
  if (t.size() > 40) throw std::invalid_argument("too long for a number");
  Number n;
  const std::string l = lower(t);
  constexpr std::string_view kNodeId = "$nodeid";
  if (const auto at = l.find('$'); at != std::string::npos) {
    std::string_view rest = std::string_view(l);
    if (rest.substr(at, kNodeId.size()) != kNodeId)
      throw std::invalid_argument("'$' must begin $NODEID");
    if (l.find('$', at + 1) != std::string::npos)
      throw std::invalid_argument("$NODEID more than once");
    const auto before = trim(rest.substr(0, at));
    const auto after = trim(rest.substr(at + kNodeId.size()));
    n.node_id = true;
    if (before.empty() && after.empty()) return n;
    if (before.empty()) {
      if (after.front() != '+') throw std::invalid_argument("expected '+' after $NODEID");
      t = trim(t.substr(t.size() - after.size() + 1));
    } else {
      if (!after.empty() || before.back() != '+')
        throw std::invalid_argument("expected N+$NODEID or $NODEID+N");
      t = trim(t.substr(0, before.size() - 1));
    }
    if (t.empty()) throw std::invalid_argument("no number beside $NODEID");
  }
  if (t.front() == '-' || t.front() == '+') {
    n.negative = t.front() == '-';
    t.remove_prefix(1);
  }
  int base = 10;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    base = 16;
    t.remove_prefix(2);
  } else if (t.size() > 1 && t[0] == '0') {
    base = 8;  // CiA 306: a leading 0 is octal
    t.remove_prefix(1);
  }
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), n.magnitude, base);
  if (ec == std::errc::result_out_of_range) throw std::invalid_argument("out of range");
  if (ec != std::errc() || end != t.data() + t.size() || t.empty())
    throw std::invalid_argument(base == 16  ? "not a hex number"
                                : base == 8 ? "not an octal number"
                                            : "not a decimal number");
  if (n.negative && n.magnitude == 0) n.negative = false;
  return n;
}

// Bits of an integer type's value; 0 for other types.
unsigned integer_bits(std::uint16_t type) {
  return type == datatype::kBoolean
             ? 1U
             : (is_integer_type(type) ? static_cast<unsigned>(8 * data_type_size(type)) : 0U);
}

}  // namespace

std::int64_t parse_eds_integer(std::string_view text, std::uint8_t node_id) {
  const auto n = parse_number(text);
  constexpr auto kMax = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  std::int64_t v = 0;
  if (n.negative) {
    if (n.magnitude > kMax + 1) throw std::invalid_argument("out of range");
    v = n.magnitude == kMax + 1 ? std::numeric_limits<std::int64_t>::min()
                                : -static_cast<std::int64_t>(n.magnitude);
  } else {
    if (n.magnitude > kMax) throw std::invalid_argument("out of range");
    v = static_cast<std::int64_t>(n.magnitude);
  }
  const std::int64_t add = n.node_id ? node_id : 0;
  if (v > std::numeric_limits<std::int64_t>::max() - add)
    throw std::invalid_argument("out of range");
  return v + add;
}

std::uint64_t parse_eds_unsigned(std::string_view text, std::uint8_t node_id) {
  const auto n = parse_number(text);
  if (n.negative) throw std::invalid_argument("negative, expected an unsigned number");
  const std::uint64_t add = n.node_id ? node_id : 0;
  if (n.magnitude > std::numeric_limits<std::uint64_t>::max() - add)
    throw std::invalid_argument("out of range");
  return n.magnitude + add;
}

namespace eds_detail {

std::optional<std::string> check_value(std::string_view value, std::uint16_t type) {
  const auto text = trim(value);
  if (text.empty()) return std::nullopt;
  if (type == datatype::kReal32 || type == datatype::kReal64) {
    const std::string t(text);
    char* end = nullptr;
    const double d = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size() || !std::isfinite(d)) return "a finite real number";
    return std::nullopt;
  }
  // Strings, DOMAIN (often NULL or a file name), TIME_OF_DAY, TIME_DIFFERENCE and types this
  // reader does not know (a DEFTYPE or DEFSTRUCT index) are kept as written.
  const auto bits = integer_bits(type);
  if (bits == 0) return std::nullopt;
  const bool is_unsigned = is_unsigned_type(type);
  // A signed type may be written as its bit pattern (INTEGER16 0xFFFF for -1), as vendors do.
  const std::uint64_t max_magnitude =
      bits == 64 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t{1} << bits) - 1;
  const std::uint64_t max_negative = is_unsigned ? 0 : std::uint64_t{1} << (bits - 1);
  const auto expected = [&](std::string_view why) {
    if (is_unsigned)
      return fmt::format("{} in 0..{}, optionally with $NODEID+ ({})", data_type_name(type),
                         max_magnitude, why);
    return fmt::format(
        "{} in -{}..{} or its bit pattern up to 0x{:X}, optionally with $NODEID+ "
        "({})",
        data_type_name(type), max_negative, max_negative - 1, max_magnitude, why);
  };
  Number n;
  try {
    n = parse_number(text);
  } catch (const std::invalid_argument& e) {
    return expected(e.what());
  }
  if (n.negative ? n.magnitude > max_negative : n.magnitude > max_magnitude)
    return expected("out of range");
  return std::nullopt;
}

}  // namespace eds_detail
}  // namespace wavebench::canopen
