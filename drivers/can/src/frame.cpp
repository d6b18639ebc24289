#include "wavebench/can/frame.hpp"

#include <algorithm>
#include <stdexcept>

namespace wavebench::can {

namespace {

Frame make_frame(std::uint32_t id, const std::uint8_t* bytes, std::size_t count) {
  if (count > kMaxDataLength) {
    throw std::invalid_argument("CAN frame data: " + std::to_string(count) +
                                " bytes, expected at most 8");
  }
  Frame f;
  f.extended = id > kStandardIdMask;
  f.id = id & (f.extended ? kExtendedIdMask : kStandardIdMask);
  f.len = static_cast<std::uint8_t>(count);
  std::copy_n(bytes, count, f.data.begin());
  return f;
}

int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

Frame Frame::make(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  return make_frame(id, bytes.begin(), bytes.size());
}

Frame Frame::make(std::uint32_t id, std::span<const std::uint8_t> bytes) {
  return make_frame(id, bytes.data(), bytes.size());
}

std::uint32_t Frame::raw_id() const noexcept {
  std::uint32_t raw = id & (extended ? kExtendedIdMask : kStandardIdMask);
  if (error) raw = (id & kExtendedIdMask) | kErrorFlag;
  if (extended) raw |= kExtendedFlag;
  if (rtr) raw |= kRtrFlag;
  return raw;
}

bool operator==(const Frame& a, const Frame& b) noexcept {
  if (a.id != b.id || a.extended != b.extended || a.rtr != b.rtr || a.error != b.error ||
      a.len != b.len) {
    return false;
  }
  if (a.rtr) return true;
  const std::size_t n = std::min<std::size_t>(a.len, kMaxDataLength);
  return std::equal(a.data.begin(), a.data.begin() + static_cast<std::ptrdiff_t>(n),
                    b.data.begin());
}

std::string to_string(const Frame& frame) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  const int digits = (frame.extended || frame.error) ? 8 : 3;
  const std::uint32_t id = frame.error ? (frame.id | kErrorFlag) : frame.id;
  for (int shift = (digits - 1) * 4; shift >= 0; shift -= 4) out += kHex[(id >> shift) & 0xFU];
  out += '#';
  if (frame.rtr) {
    out += 'R';
    if (frame.len > 0) out += static_cast<char>('0' + std::min<int>(frame.len, 8));
    return out;
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(frame.len, kMaxDataLength); ++i) {
    out += kHex[frame.data[i] >> 4];
    out += kHex[frame.data[i] & 0xFU];
  }
  return out;
}

std::optional<Frame> parse_frame(std::string_view text) {
  const auto hash = text.find('#');
  if (hash == std::string_view::npos) return std::nullopt;
  const std::string_view id_text = text.substr(0, hash);
  std::string_view data_text = text.substr(hash + 1);
  if (id_text.size() != 3 && id_text.size() != 8) return std::nullopt;
  std::uint32_t id = 0;
  for (char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) return std::nullopt;
    id = (id << 4) | static_cast<std::uint32_t>(v);
  }
  Frame f;
  if (id_text.size() == 8) {
    if ((id & kErrorFlag) != 0) {
      f.error = true;
    } else {
      f.extended = true;
    }
    id &= kExtendedIdMask;
  } else if (id > kStandardIdMask) {
    return std::nullopt;
  }
  f.id = id;
  if (!data_text.empty() && (data_text[0] == 'R' || data_text[0] == 'r')) {
    f.rtr = true;
    if (data_text.size() == 1) return f;
    if (data_text.size() != 2 || data_text[1] < '0' || data_text[1] > '8') return std::nullopt;
    f.len = static_cast<std::uint8_t>(data_text[1] - '0');
    return f;
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < data_text.size();) {
    if (data_text[i] == '.') {  // cansend allows dots between bytes
      ++i;
      continue;
    }
    if (i + 1 >= data_text.size() || n >= kMaxDataLength) return std::nullopt;
    const int hi = hex_value(data_text[i]);
    const int lo = hex_value(data_text[i + 1]);
    if (hi < 0 || lo < 0) return std::nullopt;
    f.data[n++] = static_cast<std::uint8_t>((hi << 4) | lo);
    i += 2;
  }
  f.len = static_cast<std::uint8_t>(n);
  return f;
}

}  // namespace wavebench::can
