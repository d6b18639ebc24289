#pragma once
// The objects a device client uses, written once next to each client (Cia402Drive,
// Cia406Encoder, TorqueSensor::used_objects): the EDS check before connecting and the
// commissioning check read the same list. It is the bench's policy per device class, after the
// profiles (CiA 301, 402, 406): an object a profile makes optional carries `without`, what the
// bench does when the device lacks it (an absent channel, a skipped step, a message); only the
// objects without it can make a row red.

#include <array>
#include <cstddef>
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
  // nullptr: required. Otherwise the device may lack it and this says what the bench does then.
  const char* without = nullptr;
  // A PDO communication or mapping parameter the bench writes, but reads back and uses as found
  // where the device has it read-only (pdo_adoption.hpp): `ro` / `const` in the EDS is no
  // problem for it.
  bool may_be_read_only = false;
  constexpr bool optional() const noexcept { return without != nullptr; }
};

// The CiA 301 objects every node of the bench is set up through (device type, SYNC period,
// heartbeat or else node guarding, identity, TPDO1 with one mapped object), written once for
// every device's list. The TPDO parameters may be read-only: the bench then uses the mapping it
// reads back.
inline constexpr std::size_t kNodeObjectCount = 11;
constexpr std::array<UsedObject, kNodeObjectCount> node_objects() {
  using enum UsedAccess;
  using enum UsedInPdo;
  namespace dt = datatype;
  return {{
      {0x1000, 0, "device type", dt::kUnsigned32, 0, kRead},
      {0x1006, 0, "communication cycle period", dt::kUnsigned32, 0, kReadWrite, kNone,
       "not written: the device answers every SYNC as it comes"},
      // Optional: a node without a heartbeat producer is node-guarded (CiA 301 §7.2.8.3.2).
      {0x1017, 0, "producer heartbeat time", dt::kUnsigned16, 0, kReadWrite, kNone,
       "no heartbeat producer: the node is watched by node guarding (0x100C/0x100D)"},
      {0x1018, 1, "vendor-ID", dt::kUnsigned32, 0, kRead},
      {0x1018, 2, "product code", dt::kUnsigned32, 0, kRead, kNone,
       "the product code is not compared"},
      {0x1018, 3, "revision number", dt::kUnsigned32, 0, kRead, kNone,
       "the revision is not compared"},
      {0x1018, 4, "serial number", dt::kUnsigned32, 0, kRead, kNone,
       "the device's serial number is not recorded"},
      {0x1800, 1, "TPDO1 COB-ID", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
      {0x1800, 2, "TPDO1 transmission type", dt::kUnsigned8, 0, kReadWrite, kNone, nullptr, true},
      {0x1A00, 0, "TPDO1 number of mapped objects", dt::kUnsigned8, 0, kReadWrite, kNone, nullptr,
       true},
      {0x1A00, 1, "TPDO1 mapped object 1", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
  }};
}

// node_objects() followed by a device's own objects.
template <std::size_t N>
constexpr std::array<UsedObject, kNodeObjectCount + N> with_node_objects(
    const std::array<UsedObject, N>& own) {
  std::array<UsedObject, kNodeObjectCount + N> all{};
  const auto node = node_objects();
  for (std::size_t i = 0; i < kNodeObjectCount; ++i) all[i] = node[i];
  for (std::size_t i = 0; i < N; ++i) all[kNodeObjectCount + i] = own[i];
  return all;
}

std::string describe(const UsedObject& object);  // "0x6041:0 statusword"

// What `eds` says against each used object: a missing required object, another data type, an
// access that does not allow the use (but `ro`/`const` on one marked may_be_read_only), not
// PDO-mappable where it goes in a PDO. Empty: agreed. An optional object missing from the EDS,
// or described otherwise than the bench uses it, is not a problem (the bench does without it). An object the EDS has a section for but could not read (Eds::problem) is
// "in the EDS but unreadable: <why>".
std::vector<std::string> check_against_eds(std::span<const UsedObject> used, const Eds& eds);

}  // namespace wavebench::canopen
