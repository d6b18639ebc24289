#pragma once
// The objects a device client uses, written once next to each client (Cia402Drive,
// Cia406Encoder, TorqueSensor::used_objects): the EDS check before connecting and the
// commissioning check read the same list.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "wavebench/canopen/eds.hpp"

namespace wavebench::canopen {

enum class UsedAccess { kRead, kWrite, kReadWrite };
enum class UsedInPdo { kNone, kTpdo, kRpdo };

struct UsedObject {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  const char* name = "";
  std::uint16_t data_type = 0;
  std::uint16_t alt_data_type = 0;  // a second accepted type (0: none), e.g. 0x6502 u16 or u32
  UsedAccess access = UsedAccess::kRead;
  UsedInPdo pdo = UsedInPdo::kNone;
  bool optional = false;  // the client copes without it (an absent channel, a skipped write)
};

std::string describe(const UsedObject& object);  // "0x6041:0 statusword"

// What `eds` says against each used object: a missing required object, another data type, an
// access that does not allow the use, not PDO-mappable where it goes in a PDO. Empty: agreed.
// An optional object missing from the EDS is not a problem.
std::vector<std::string> check_against_eds(std::span<const UsedObject> used, const Eds& eds);

}  // namespace wavebench::canopen
