#pragma once
// Object values as text for the commissioning CLI: the types u8 u16 u32 u64 i8 i16 i32 i64 f32
// f64 str hex, parsed into little-endian bytes and printed back.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace wavebench::canopen {

bool is_value_type(std::string_view type) noexcept;
// Throws std::invalid_argument naming the type, the text and what was expected.
std::vector<std::uint8_t> encode_value(std::string_view type, std::string_view text);
// With a type: the value in that type (throws on a size mismatch). Without (empty type): every
// plausible reading of the bytes.
std::string format_value(std::string_view type, std::span<const std::uint8_t> bytes);
std::string hex_bytes(std::span<const std::uint8_t> bytes);
// Index, sub-index and node numbers: a 0x prefix means hex, otherwise decimal. Throws naming
// `what`, the text and the range.
std::uint32_t parse_number(std::string_view what, std::string_view text, std::uint32_t max);

}  // namespace wavebench::canopen
