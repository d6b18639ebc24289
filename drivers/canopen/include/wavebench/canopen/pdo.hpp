#pragma once
// PDO mapping: configuration by SDO in the CiA 301 remap order, and the codec that packs and
// unpacks mapped values (little-endian, bit-packed in mapping order).

#include <cstdint>
#include <span>
#include <system_error>
#include <vector>

#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::canopen {

class SdoClient;

struct PdoEntry {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;  // 1..64
  // The mapping object's value: index << 16 | sub << 8 | bits.
  std::uint32_t encode() const noexcept {
    return static_cast<std::uint32_t>(index) << 16 | static_cast<std::uint32_t>(sub) << 8 | bits;
  }
  static PdoEntry decode(std::uint32_t raw) noexcept {
    return {static_cast<std::uint16_t>(raw >> 16), static_cast<std::uint8_t>(raw >> 8),
            static_cast<std::uint8_t>(raw)};
  }
};

struct PdoConfig {
  std::uint32_t cob_id = 0;
  std::uint8_t transmission_type = 1;  // 1 = synchronous, every SYNC
  std::uint16_t event_timer_ms = 0;    // written only when non-zero
  std::vector<PdoEntry> entries;
};

enum class PdoDirection { transmit, receive };  // seen from the device: TPDO or RPDO

// Objects: communication 0x1800+n-1 / 0x1400+n-1, mapping 0x1A00+n-1 / 0x1600+n-1 (n = 1..512).
// Order: COB-ID with bit 31 set, transmission type (and event timer), mapping sub0 = 0, each
// entry, sub0 = count, COB-ID with bit 31 clear. Stops at the first abort.
void configure_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, const PdoConfig& config,
                   std::error_code& ec) noexcept;
void configure_pdo(SdoClient& sdo, PdoDirection direction, unsigned number,
                   const PdoConfig& config);
// Disables a PDO (COB-ID bit 31 set).
void disable_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, std::uint32_t cob_id,
                 std::error_code& ec) noexcept;

// Bit positions of mapped values; throws std::invalid_argument when the mapping exceeds 64 bits.
class PdoLayout {
 public:
  explicit PdoLayout(std::vector<PdoEntry> entries);
  const std::vector<PdoEntry>& entries() const noexcept { return entries_; }
  std::size_t size() const noexcept { return entries_.size(); }
  std::size_t length_bytes() const noexcept { return (total_bits_ + 7) / 8; }

  // Raw value of entry i, zero-extended; nullopt-free: a frame shorter than the mapping is
  // rejected by `fits` first.
  bool fits(const can::Frame& frame) const noexcept { return frame.len >= length_bytes(); }
  std::uint64_t raw(const can::Frame& frame, std::size_t i) const noexcept;
  std::int64_t signed_value(const can::Frame& frame, std::size_t i) const noexcept;
  float f32(const can::Frame& frame, std::size_t i) const noexcept;
  double f64(const can::Frame& frame, std::size_t i) const noexcept;
  void set_raw(can::Frame& frame, std::size_t i, std::uint64_t value) const noexcept;
  can::Frame make_frame(std::uint32_t cob_id, std::span<const std::uint64_t> raw_values) const;

 private:
  std::vector<PdoEntry> entries_;
  std::vector<unsigned> offsets_;
  unsigned total_bits_ = 0;
};

std::uint64_t extract_bits(std::span<const std::uint8_t> data, unsigned offset,
                           unsigned bits) noexcept;
void insert_bits(std::span<std::uint8_t> data, unsigned offset, unsigned bits,
                 std::uint64_t value) noexcept;

}  // namespace wavebench::canopen
