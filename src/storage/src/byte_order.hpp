#pragma once
// Little-endian field encoding for the on-disk formats, independent of the host.

#include <bit>
#include <cstddef>
#include <cstdint>

namespace wavebench::storage::detail {

inline void put_u32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
inline void put_u64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
inline std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}
inline std::uint64_t get_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}
inline void put_f64(unsigned char* p, double v) {
  put_u64(p, std::bit_cast<std::uint64_t>(v));
}
inline double get_f64(const unsigned char* p) {
  return std::bit_cast<double>(get_u64(p));
}

inline std::uint32_t fnv1a32(const unsigned char* p, std::size_t n) {
  std::uint32_t h = 2166136261u;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= p[i];
    h *= 16777619u;
  }
  return h;
}

}  // namespace wavebench::storage::detail
