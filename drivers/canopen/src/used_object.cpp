#include "wavebench/canopen/used_object.hpp"

#include <fmt/format.h>

namespace wavebench::canopen {

std::string describe(const UsedObject& object) {
  return fmt::format("0x{:04X}:{} {}", object.index, object.sub, object.name);
}

namespace {

bool agrees(const UsedObject& u, const EdsObject& o) {
  const bool type_ok =
      o.data_type == u.data_type || (u.alt_data_type != 0 && o.data_type == u.alt_data_type);
  const bool need_read = u.access != UsedAccess::kWrite || u.pdo == UsedInPdo::kTpdo;
  const bool need_write = u.access != UsedAccess::kRead || u.pdo == UsedInPdo::kRpdo;
  const bool access_ok = (!need_read || readable(o.access)) &&
                         (!need_write || writable(o.access) || u.may_be_read_only);
  return type_ok && access_ok && (u.pdo == UsedInPdo::kNone || o.pdo_mapping);
}

}  // namespace

std::vector<std::string> check_against_eds(std::span<const UsedObject> used, const Eds& eds) {
  std::vector<std::string> problems;
  for (const auto& u : used) {
    const auto* o = eds.find(u.index, u.sub);
    if (!o) {
      // An object the file has a section for but that could not be read says why.
      if (u.optional()) continue;
      const auto why = eds.problem(u.index, u.sub);
      problems.push_back(describe(u) +
                         (why ? ": in the EDS but unreadable: " + *why : ": not in the EDS"));
      continue;
    }
    // An optional object the EDS describes otherwise (read-only 0x1017, 0x60F4 not mappable)
    // is one the bench does without, as when the device lacks it: not a refusal.
    if (u.optional() && !agrees(u, *o)) continue;
    if (o->data_type != u.data_type && (u.alt_data_type == 0 || o->data_type != u.alt_data_type)) {
      problems.push_back(
          fmt::format("{}: EDS DataType {}, expected {}{}", describe(u),
                      data_type_name(o->data_type), data_type_name(u.data_type),
                      u.alt_data_type ? " or " + data_type_name(u.alt_data_type) : std::string()));
    }
    const bool need_read = u.access != UsedAccess::kWrite || u.pdo == UsedInPdo::kTpdo;
    const bool need_write = u.access != UsedAccess::kRead || u.pdo == UsedInPdo::kRpdo;
    // A PDO parameter the bench cannot write is read back and used as found.
    const bool write_refused = need_write && !writable(o->access) && !u.may_be_read_only;
    if ((need_read && !readable(o->access)) || write_refused) {
      problems.push_back(fmt::format("{}: EDS AccessType {}, the bench {}", describe(u),
                                     to_string(o->access),
                                     need_read && need_write ? "reads and writes it"
                                     : need_read             ? "reads it"
                                                             : "writes it"));
    }
    if (u.pdo != UsedInPdo::kNone && !o->pdo_mapping) {
      problems.push_back(fmt::format("{}: EDS PDOMapping 0, the bench maps it in a {}", describe(u),
                                     u.pdo == UsedInPdo::kTpdo ? "TPDO" : "RPDO"));
    }
  }
  return problems;
}

}  // namespace wavebench::canopen
