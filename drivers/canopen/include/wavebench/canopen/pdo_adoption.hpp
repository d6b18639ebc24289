#pragma once
// PDOs whose mapping cannot be written (issue 20). Some devices have read-only PDO communication
// and mapping parameters (a Faulhaber EDS says so), or refuse a remap with an SDO abort. The
// bench then reads the PDO back (COB-ID, transmission type, mapping) and uses it as found when
// it carries what the bench needs, wherever and at whatever bit offset the device put it.
//
//   configure_or_read_back  tries the bench's mapping; on a refusal reads the PDO back
//   use_tpdos               finds each object a device needs in those PDOs (any PDO, any
//                           position), makes a used fixed PDO valid and synchronous where the
//                           device lets it, and says exactly what is missing otherwise
//
// Refusals taken as "this mapping cannot be written": 06010002 read-only, 06090030 value range,
// 06040041 not mappable, 06040042 PDO length exceeded, 08000020..08000022 (cannot be stored
// now / local control / device state). Any other failure (a timeout) stays an error.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "wavebench/canopen/pdo.hpp"

namespace wavebench::canopen {

class SdoClient;

struct PdoAdoption {
  PdoDirection direction = PdoDirection::transmit;
  unsigned number = 0;      // 1..512
  PdoConfig actual;         // as written, or as read back (COB-ID bit 31 as the device has it)
  bool fixed = false;       // the mapping could not be written: read back, used as found
  std::error_code refusal;  // fixed: the abort that refused the bench's mapping
};

// The aborts listed above.
bool is_fixed_mapping_refusal(const std::error_code& ec) noexcept;

// Reads a PDO's COB-ID (sub 1), transmission type (sub 2) and mapping (sub 0, each entry).
PdoConfig read_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, std::error_code& ec);

// configure_pdo(wanted); when the device refuses it with one of the aborts above, the PDO as the
// device has it (fixed). Throws std::system_error naming the PDO on any other failure, or when
// the read-back fails.
PdoAdoption configure_or_read_back(SdoClient& sdo, PdoDirection direction, unsigned number,
                                   const PdoConfig& wanted);
// The read-back half of it, after configure_pdo failed with `refusal`.
PdoAdoption read_back_refused(SdoClient& sdo, PdoDirection direction, unsigned number,
                              std::error_code refusal);

// "0x6064:0/32, 0x6041:0/16"
std::string describe_entries(const std::vector<PdoEntry>& entries);
// "TPDO1 [0x6041:0/16, 0x6064:0/32]", or "TPDO1 fixed [...]" when used as found.
std::string describe(const PdoAdoption& pdo);

// An object a device needs from its TPDOs. `bits` is its type's size; a mapping with fewer bits
// is refused unless `min_bits` (documented for that object) allows it.
struct NeededObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;
  const char* name = "";
  bool optional = false;      // the device goes on without it (an absent channel)
  std::uint8_t min_bits = 0;  // 0: `bits`
};

// Where a needed object is: PDO `pdo` of AdoptedTpdos::pdos, entry `entry` of its mapping.
struct ObjectPlace {
  std::size_t pdo = 0;
  std::size_t entry = 0;
};

// The TPDOs a device uses, and where each object it needs is in them.
class AdoptedTpdos {
 public:
  AdoptedTpdos() = default;
  AdoptedTpdos(std::vector<PdoAdoption> pdos, std::vector<std::optional<ObjectPlace>> places);

  const std::vector<PdoAdoption>& pdos() const noexcept { return pdos_; }
  // The PDOs' configurations in the same order (CanopenDevice::tpdos()).
  std::vector<PdoConfig> configs() const;
  bool any_fixed() const noexcept;
  // "fixed mapping, used as found: TPDO1 [0x6064:0/32, 0x6041:0/16], TPDO2 [0x606C:0/32]"
  // (with the PDOs written as the bench maps them after it); empty when none is fixed.
  std::string summary() const;

  // Whether needed object k (the index into use_tpdos' `needed`) was found.
  bool has(std::size_t k) const noexcept { return k < places_.size() && places_[k].has_value(); }
  // Needed object k in a frame of PDO `pdo`: nullopt when it is elsewhere (or absent), or the
  // frame is shorter than that PDO's mapping.
  std::optional<std::uint64_t> raw(std::size_t k, std::size_t pdo,
                                   const can::Frame& frame) const noexcept;
  // The same, sign-extended from its mapped length.
  std::optional<std::int64_t> signed_value(std::size_t k, std::size_t pdo,
                                           const can::Frame& frame) const noexcept;
  // The frame is as long as PDO `pdo`'s mapping.
  bool fits(std::size_t pdo, const can::Frame& frame) const noexcept {
    return pdo < layouts_.size() && layouts_[pdo].fits(frame);
  }

 private:
  std::vector<PdoAdoption> pdos_;
  std::vector<PdoLayout> layouts_;
  std::vector<std::optional<ObjectPlace>> places_;
};

// Finds each of `needed` in `candidates` (the first mapping of it in PDO order). A PDO the bench
// wrote is always used; a fixed one only when it carries a needed object, and then it must be
// valid (COB-ID bit 31 clear) and sent on every SYNC (transmission type 1): where it is not, the
// bench writes the COB-ID / the type, and refuses when the device does not take it. Throws
// std::runtime_error naming the PDOs as found and what is missing, e.g. "TPDO1 fixed
// [0x6064:0/32], TPDO2 fixed [0x606C:0/32]: 0x6041:0 statusword not mapped in any TPDO".
AdoptedTpdos use_tpdos(SdoClient& sdo, std::vector<PdoAdoption> candidates,
                       std::span<const NeededObject> needed);

}  // namespace wavebench::canopen
