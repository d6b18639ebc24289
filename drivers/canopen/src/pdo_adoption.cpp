#include "wavebench/canopen/pdo_adoption.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "wavebench/canopen/sdo_abort.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {
namespace {

constexpr std::uint32_t kCobIdExtended = 0x20000000U;
constexpr unsigned kMaxMappedEntries = 64;  // CiA 301: sub-indices 1..64 of the mapping object

std::uint16_t communication_index(PdoDirection direction, unsigned number) {
  return static_cast<std::uint16_t>((direction == PdoDirection::transmit ? 0x1800 : 0x1400) +
                                    number - 1);
}

std::uint16_t mapping_index(PdoDirection direction, unsigned number) {
  return static_cast<std::uint16_t>((direction == PdoDirection::transmit ? 0x1A00 : 0x1600) +
                                    number - 1);
}

std::string pdo_name(PdoDirection direction, unsigned number) {
  return fmt::format("{}{}", direction == PdoDirection::transmit ? "TPDO" : "RPDO", number);
}

std::string abort_text_of(const std::error_code& ec) {
  return fmt::format("SDO abort {:08X} ({})", abort_code_of(ec), ec.message());
}

bool is(const std::error_code& ec, SdoAbort abort) {
  return ec == make_error_code(abort);
}

std::string transmission_text(std::uint8_t type) {
  if (type == 0) return "acyclic synchronous: sent on a SYNC only when its values change";
  if (type <= 240) return fmt::format("sent once every {} SYNCs, not on every SYNC", type);
  if (type <= 253) return "reserved / remote request only, not on SYNC";
  return "event-driven, not on SYNC";
}

// A fixed PDO the bench uses must arrive once per SYNC on a valid COB-ID: writes what is
// missing (the communication parameters may be writable where the mapping is not). Returns
// what stays wrong, empty when the PDO is usable.
std::string make_usable(SdoClient& sdo, PdoAdoption& pdo) {
  const auto comm = communication_index(pdo.direction, pdo.number);
  std::string wrong;
  if (pdo.actual.cob_id & kCobIdExtended) {
    return fmt::format("COB-ID 0x{:04X}:1 = 0x{:08X} is a 29-bit identifier: expected 11 bits",
                       comm, pdo.actual.cob_id);
  }
  if (pdo.direction == PdoDirection::transmit && pdo.actual.transmission_type != 1) {
    // The type may only change while the PDO is invalid (CiA 301 §7.5.2.35).
    std::error_code ec;
    const std::uint32_t cob = pdo.actual.cob_id & ~kCobIdInvalid;
    if (!(pdo.actual.cob_id & kCobIdInvalid))
      sdo.write<std::uint32_t>(comm, 1, cob | kCobIdInvalid, ec);
    if (!ec) sdo.write<std::uint8_t>(comm, 2, 1, ec);
    if (ec) {
      wrong = fmt::format("transmission type 0x{:04X}:2 = {} ({}) and it cannot be written ({})",
                          comm, pdo.actual.transmission_type,
                          transmission_text(pdo.actual.transmission_type), abort_text_of(ec));
      // Put a PDO the bench invalidated back as it was.
      if (!(pdo.actual.cob_id & kCobIdInvalid)) {
        std::error_code ignored;
        sdo.write<std::uint32_t>(comm, 1, pdo.actual.cob_id, ignored);
      }
      return wrong;
    }
    pdo.actual.transmission_type = 1;
    pdo.actual.cob_id |= kCobIdInvalid;  // as the bench left it: validated below
  }
  if (pdo.actual.cob_id & kCobIdInvalid) {
    std::error_code ec;
    sdo.write<std::uint32_t>(comm, 1, pdo.actual.cob_id & ~kCobIdInvalid, ec);
    if (ec) {
      return fmt::format(
          "disabled (COB-ID 0x{:04X}:1 = 0x{:08X}, bit 31 set) and its COB-ID "
          "cannot be written ({})",
          comm, pdo.actual.cob_id, abort_text_of(ec));
    }
    pdo.actual.cob_id &= ~kCobIdInvalid;
  }
  return wrong;
}

std::string list(const std::vector<PdoAdoption>& pdos) {
  std::string out;
  for (const auto& p : pdos) out += (out.empty() ? "" : ", ") + describe(p);
  return out.empty() ? "no TPDO" : out;
}

std::string object_text(const NeededObject& n) {
  return fmt::format("0x{:04X}:{} {}", n.index, n.sub, n.name);
}

}  // namespace

bool is_fixed_mapping_refusal(const std::error_code& ec) noexcept {
  return is(ec, SdoAbort::read_only) || is(ec, SdoAbort::invalid_value) ||
         is(ec, SdoAbort::not_mappable) || is(ec, SdoAbort::pdo_too_long) ||
         is(ec, SdoAbort::data_transfer) || is(ec, SdoAbort::local_control) ||
         is(ec, SdoAbort::device_state);
}

PdoConfig read_pdo(SdoClient& sdo, PdoDirection direction, unsigned number, std::error_code& ec) {
  PdoConfig config;
  ec.clear();
  if (number < 1 || number > 512) {
    ec = make_error_code(SdoAbort::invalid_value);
    return config;
  }
  const auto comm = communication_index(direction, number);
  const auto map = mapping_index(direction, number);
  config.cob_id = sdo.read<std::uint32_t>(comm, 1, ec);
  if (ec) return config;
  config.transmission_type = sdo.read<std::uint8_t>(comm, 2, ec);
  if (ec) return config;
  const auto count = sdo.read<std::uint8_t>(map, 0, ec);
  if (ec) return config;
  if (count > kMaxMappedEntries) {
    ec = make_error_code(SdoAbort::invalid_value);
    return config;
  }
  for (std::uint8_t k = 1; k <= count; ++k) {
    config.entries.push_back(PdoEntry::decode(sdo.read<std::uint32_t>(map, k, ec)));
    if (ec) return config;
  }
  return config;
}

PdoAdoption configure_or_read_back(SdoClient& sdo, PdoDirection direction, unsigned number,
                                   const PdoConfig& wanted) {
  std::error_code ec;
  configure_pdo(sdo, direction, number, wanted, ec);
  if (!ec) {
    PdoAdoption out{direction, number, wanted, false, {}};
    out.actual.cob_id &= ~kCobIdInvalid;
    return out;
  }
  if (!is_fixed_mapping_refusal(ec)) {
    throw std::system_error(ec, pdo_name(direction, number) + " of node " +
                                    std::to_string(sdo.node()) + " configuration");
  }
  return read_back_refused(sdo, direction, number, ec);
}

PdoAdoption read_back_refused(SdoClient& sdo, PdoDirection direction, unsigned number,
                              std::error_code refusal) {
  PdoAdoption out{direction, number, {}, true, refusal};
  std::error_code ec;
  out.actual = read_pdo(sdo, direction, number, ec);
  if (ec) {
    throw std::system_error(ec, pdo_name(direction, number) + " of node " +
                                    std::to_string(sdo.node()) + ": mapping refused (" +
                                    abort_text_of(refusal) + "), and reading it back failed");
  }
  return out;
}

std::string describe_entries(const std::vector<PdoEntry>& entries) {
  std::string out;
  for (const auto& e : entries)
    out += fmt::format("{}0x{:04X}:{}/{}", out.empty() ? "" : ", ", e.index, e.sub, e.bits);
  return out;
}

std::string describe(const PdoAdoption& pdo) {
  return fmt::format("{}{} [{}]", pdo_name(pdo.direction, pdo.number), pdo.fixed ? " fixed" : "",
                     describe_entries(pdo.actual.entries));
}

AdoptedTpdos::AdoptedTpdos(std::vector<PdoAdoption> pdos,
                           std::vector<std::optional<ObjectPlace>> places)
    : pdos_(std::move(pdos)), places_(std::move(places)) {
  for (const auto& p : pdos_) layouts_.emplace_back(p.actual.entries);
}

std::vector<PdoConfig> AdoptedTpdos::configs() const {
  std::vector<PdoConfig> out;
  for (const auto& p : pdos_) out.push_back(p.actual);
  return out;
}

bool AdoptedTpdos::any_fixed() const noexcept {
  for (const auto& p : pdos_)
    if (p.fixed) return true;
  return false;
}

std::string AdoptedTpdos::summary() const {
  if (!any_fixed()) return {};
  std::string fixed;
  std::string written;
  for (const auto& p : pdos_) {
    const auto text =
        fmt::format("{} [{}]", pdo_name(p.direction, p.number), describe_entries(p.actual.entries));
    auto& into = p.fixed ? fixed : written;
    into += (into.empty() ? "" : ", ") + text;
  }
  return "fixed mapping, used as found: " + fixed +
         (written.empty() ? "" : "; mapped by the bench: " + written);
}

std::optional<std::uint64_t> AdoptedTpdos::raw(std::size_t k, std::size_t pdo,
                                               const can::Frame& frame) const noexcept {
  if (!has(k) || places_[k]->pdo != pdo || !fits(pdo, frame)) return std::nullopt;
  return layouts_[pdo].raw(frame, places_[k]->entry);
}

std::optional<std::int64_t> AdoptedTpdos::signed_value(std::size_t k, std::size_t pdo,
                                                       const can::Frame& frame) const noexcept {
  if (!has(k) || places_[k]->pdo != pdo || !fits(pdo, frame)) return std::nullopt;
  return layouts_[pdo].signed_value(frame, places_[k]->entry);
}

AdoptedTpdos use_tpdos(SdoClient& sdo, std::vector<PdoAdoption> candidates,
                       std::span<const NeededObject> needed) {
  // Where each needed object is, in the candidates' numbering; the first mapping of it wins.
  std::vector<std::optional<ObjectPlace>> found(needed.size());
  std::vector<bool> too_short(needed.size());
  std::string short_objects;
  for (std::size_t k = 0; k < needed.size(); ++k) {
    const auto& n = needed[k];
    for (std::size_t p = 0; p < candidates.size() && !found[k]; ++p) {
      const auto& entries = candidates[p].actual.entries;
      for (std::size_t e = 0; e < entries.size(); ++e) {
        if (entries[e].index != n.index || entries[e].sub != n.sub) continue;
        const unsigned min_bits = n.min_bits ? n.min_bits : n.bits;
        if (entries[e].bits < min_bits || entries[e].bits > 64) {
          short_objects += fmt::format(
              "; {} is mapped in {} with {} bits: expected {}{}", object_text(n),
              pdo_name(candidates[p].direction, candidates[p].number), entries[e].bits, n.bits,
              n.min_bits && n.min_bits < n.bits ? fmt::format(" (at least {})", n.min_bits) : "");
          too_short[k] = true;
          continue;
        }
        found[k] = ObjectPlace{p, e};
        break;
      }
    }
  }
  // The PDOs used: those the bench wrote, and the fixed ones that carry something needed.
  std::vector<bool> used(candidates.size());
  for (std::size_t p = 0; p < candidates.size(); ++p) used[p] = !candidates[p].fixed;
  for (const auto& f : found)
    if (f) used[f->pdo] = true;

  std::string problems = short_objects;
  for (std::size_t k = 0; k < needed.size(); ++k) {
    if (!found[k] && !too_short[k] && !needed[k].optional)
      problems += fmt::format("; {} not mapped in any TPDO", object_text(needed[k]));
  }
  std::vector<PdoAdoption> pdos;
  std::vector<std::size_t> renumber(candidates.size());
  for (std::size_t p = 0; p < candidates.size(); ++p) {
    if (!used[p]) continue;
    if (candidates[p].fixed) {
      // Only when everything needed is there: a refused bench leaves the PDOs as they were.
      if (problems.empty()) {
        if (const auto wrong = make_usable(sdo, candidates[p]); !wrong.empty())
          problems += fmt::format("; {} is {}", describe(candidates[p]), wrong);
      }
      try {
        PdoLayout check(candidates[p].actual.entries);
      } catch (const std::invalid_argument& e) {
        problems += fmt::format("; {}: {}", describe(candidates[p]), e.what());
      }
    }
    renumber[p] = pdos.size();
    pdos.push_back(candidates[p]);
  }
  if (!problems.empty()) throw std::runtime_error(list(candidates) + ":" + problems.substr(1));
  for (auto& f : found)
    if (f) f->pdo = renumber[f->pdo];
  return AdoptedTpdos(std::move(pdos), std::move(found));
}

}  // namespace wavebench::canopen
