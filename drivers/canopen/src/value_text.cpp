#include "wavebench/canopen/value_text.hpp"

#include <fmt/format.h>

#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::canopen {

namespace {

[[noreturn]] void bad(std::string_view type, std::string_view text, std::string_view expected) {
  throw std::invalid_argument(
      fmt::format("value '{}' for type {}: expected {}", text, type, expected));
}

template <typename T>
std::vector<std::uint8_t> bytes_of(T v) {
  std::vector<std::uint8_t> out(sizeof(T));
  std::memcpy(out.data(), &v, sizeof(T));
  return out;
}

template <typename T>
T parse_integer(std::string_view type, std::string_view text) {
  std::string_view digits = text;
  int base = 10;
  bool negative = false;
  if (!digits.empty() && digits[0] == '-') {
    negative = true;
    digits.remove_prefix(1);
  }
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    base = 16;
    digits.remove_prefix(2);
  }
  unsigned long long magnitude = 0;
  const auto [ptr, ec] =
      std::from_chars(digits.data(), digits.data() + digits.size(), magnitude, base);
  const auto expected = fmt::format("an integer in [{}, {}]", std::numeric_limits<T>::min(),
                                    std::numeric_limits<T>::max());
  if (digits.empty() || ec != std::errc{} || ptr != digits.data() + digits.size()) {
    bad(type, text, expected);
  }
  if constexpr (std::is_signed_v<T>) {
    const auto limit = negative ? static_cast<unsigned long long>(std::numeric_limits<T>::max()) + 1
                                : static_cast<unsigned long long>(std::numeric_limits<T>::max());
    if (magnitude > limit) bad(type, text, expected);
    if (negative) return static_cast<T>(-static_cast<long long>(magnitude - 1) - 1);
    return static_cast<T>(magnitude);
  } else {
    if (negative || magnitude > std::numeric_limits<T>::max()) bad(type, text, expected);
    return static_cast<T>(magnitude);
  }
}

template <typename T>
T parse_real(std::string_view type, std::string_view text) {
  const std::string s(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) bad(type, text, "a real number");
  return static_cast<T>(v);
}

template <typename T>
T load(std::span<const std::uint8_t> bytes) {
  T v{};
  std::memcpy(&v, bytes.data(), sizeof(T));
  return v;
}

}  // namespace

bool is_value_type(std::string_view type) noexcept {
  for (const char* t :
       {"u8", "u16", "u32", "u64", "i8", "i16", "i32", "i64", "f32", "f64", "str", "hex"}) {
    if (type == t) return true;
  }
  return false;
}

std::string hex_bytes(std::span<const std::uint8_t> bytes) {
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i) out += ' ';
    out += fmt::format("{:02X}", bytes[i]);
  }
  return out;
}

std::vector<std::uint8_t> encode_value(std::string_view type, std::string_view text) {
  if (type == "u8") return bytes_of(parse_integer<std::uint8_t>(type, text));
  if (type == "u16") return bytes_of(parse_integer<std::uint16_t>(type, text));
  if (type == "u32") return bytes_of(parse_integer<std::uint32_t>(type, text));
  if (type == "u64") return bytes_of(parse_integer<std::uint64_t>(type, text));
  if (type == "i8") return bytes_of(parse_integer<std::int8_t>(type, text));
  if (type == "i16") return bytes_of(parse_integer<std::int16_t>(type, text));
  if (type == "i32") return bytes_of(parse_integer<std::int32_t>(type, text));
  if (type == "i64") return bytes_of(parse_integer<std::int64_t>(type, text));
  if (type == "f32") return bytes_of(parse_real<float>(type, text));
  if (type == "f64") return bytes_of(parse_real<double>(type, text));
  if (type == "str") return {text.begin(), text.end()};
  if (type == "hex") {
    std::vector<std::uint8_t> out;
    std::string digits;
    for (char c : text) {
      if (c == ' ' || c == ':' || c == '.' || c == '-') continue;
      if (!std::isxdigit(static_cast<unsigned char>(c))) bad(type, text, "hex digits in pairs");
      digits += c;
    }
    if (digits.size() % 2 != 0) bad(type, text, "hex digits in pairs");
    for (std::size_t i = 0; i < digits.size(); i += 2) {
      out.push_back(static_cast<std::uint8_t>(std::stoul(digits.substr(i, 2), nullptr, 16)));
    }
    return out;
  }
  throw std::invalid_argument(fmt::format(
      "type '{}': expected one of u8 u16 u32 u64 i8 i16 i32 i64 f32 f64 str hex", type));
}

std::string format_value(std::string_view type, std::span<const std::uint8_t> b) {
  auto need = [&](std::size_t n) {
    if (b.size() != n) {
      throw std::invalid_argument(
          fmt::format("value of {} bytes ({}) for type {}: expected {} bytes", b.size(),
                      hex_bytes(b), type, n));
    }
  };
  if (type == "u8") return need(1), fmt::format("{}", load<std::uint8_t>(b));
  if (type == "u16") return need(2), fmt::format("{}", load<std::uint16_t>(b));
  if (type == "u32") return need(4), fmt::format("{}", load<std::uint32_t>(b));
  if (type == "u64") return need(8), fmt::format("{}", load<std::uint64_t>(b));
  if (type == "i8") return need(1), fmt::format("{}", load<std::int8_t>(b));
  if (type == "i16") return need(2), fmt::format("{}", load<std::int16_t>(b));
  if (type == "i32") return need(4), fmt::format("{}", load<std::int32_t>(b));
  if (type == "i64") return need(8), fmt::format("{}", load<std::int64_t>(b));
  if (type == "f32") return need(4), fmt::format("{}", load<float>(b));
  if (type == "f64") return need(8), fmt::format("{}", load<double>(b));
  if (type == "str") return std::string(b.begin(), b.end());
  if (type == "hex") return hex_bytes(b);
  if (!type.empty()) (void)encode_value(type, "0");  // throws the list of types
  // Untyped: the unsigned value for the usual integer sizes, the text if it reads as text.
  std::string out = hex_bytes(b);
  std::uint64_t u = 0;
  if (b.size() == 1 || b.size() == 2 || b.size() == 4 || b.size() == 8) {
    std::memcpy(&u, b.data(), b.size());
    out = fmt::format("0x{:0{}X} ({}) [{}]", u, b.size() * 2, u, out);
  }
  bool printable = !b.empty();
  for (auto c : b) printable = printable && (std::isprint(c) || c == '\n' || c == '\t' || c == 0);
  if (printable && b.size() > 1) {
    std::string text(b.begin(), b.end());
    while (!text.empty() && text.back() == '\0') text.pop_back();
    out += fmt::format(" \"{}\"", text);
  }
  return out;
}

std::uint32_t parse_number(std::string_view what, std::string_view text, std::uint32_t max) {
  std::string_view digits = text;
  int base = 10;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    base = 16;
    digits.remove_prefix(2);
  }
  std::uint32_t v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v, base);
  if (digits.empty() || ec != std::errc{} || ptr != digits.data() + digits.size() || v > max) {
    throw std::invalid_argument(
        fmt::format("{} '{}': expected a number 0..{} (0x prefix for hex)", what, text, max));
  }
  return v;
}

}  // namespace wavebench::canopen
