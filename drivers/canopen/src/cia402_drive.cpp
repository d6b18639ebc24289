#include "wavebench/canopen/cia402_drive.hpp"

#include <fmt/format.h>

#include <memory>

#include "wavebench/can/event_loop.hpp"

namespace wavebench::canopen {

namespace {

constexpr std::uint16_t kControlword = 0x6040;
constexpr std::uint16_t kStatusword = 0x6041;
constexpr std::uint16_t kErrorCode = 0x603F;
constexpr std::uint16_t kModes = 0x6060;
constexpr std::uint16_t kModesDisplay = 0x6061;
constexpr std::uint16_t kTargetPosition = 0x607A;
constexpr std::uint16_t kTargetVelocity = 0x60FF;
constexpr std::uint16_t kProfileVelocity = 0x6081;
constexpr std::uint16_t kAcceleration = 0x6083;
constexpr std::uint16_t kDeceleration = 0x6084;
constexpr std::uint16_t kFollowingError = 0x60F4;

class Cia402Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "cia402"; }
  std::string message(int value) const override {
    switch (static_cast<Cia402Errc>(value)) {
      case Cia402Errc::cannot_reach_state:
        return "drive did not reach the requested state";
      case Cia402Errc::fault:
        return "drive in fault";
      case Cia402Errc::mode_not_accepted:
        return "mode of operation not accepted";
      case Cia402Errc::set_point_not_acknowledged:
        return "set-point not acknowledged";
      case Cia402Errc::following_error:
        return "following error";
      case Cia402Errc::not_enabled:
        return "operation not enabled";
      case Cia402Errc::target_not_reached:
        return "target not reached in time";
    }
    return "unknown CiA 402 error";
  }
};

bool following_error_bit(std::uint16_t sw, std::optional<OperationMode> mode) noexcept {
  return (sw & statusword::bit13) != 0 &&
         (mode == OperationMode::profile_position || mode == OperationMode::cyclic_sync_position);
}

}  // namespace

const std::error_category& cia402_category() noexcept {
  static const Cia402Category category;
  return category;
}

std::error_code make_error_code(Cia402Errc e) noexcept {
  return {static_cast<int>(e), cia402_category()};
}

namespace {
using enum UsedAccess;
using enum UsedInPdo;
namespace dt = datatype;

// SDO: the state machine, modes, profile moves and velocity; TPDO1 statusword and position,
// TPDO2 velocity and following error (the bench's drive device); the controlword is RPDO-mappable
// for the quick stop. The TPDO parameters may be read-only (a fixed mapping, used as found).
constexpr auto kDriveObjects = with_node_objects(std::to_array<UsedObject>({
    {0x1A00, 2, "TPDO1 mapped object 2", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
    {0x1801, 1, "TPDO2 COB-ID", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
    {0x1801, 2, "TPDO2 transmission type", dt::kUnsigned8, 0, kReadWrite, kNone, nullptr, true},
    {0x1A01, 0, "TPDO2 number of mapped objects", dt::kUnsigned8, 0, kReadWrite, kNone, nullptr,
     true},
    {0x1A01, 1, "TPDO2 mapped object 1", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
    {0x1A01, 2, "TPDO2 mapped object 2", dt::kUnsigned32, 0, kReadWrite, kNone, nullptr, true},
    {0x603F, 0, "error code", dt::kUnsigned16, 0, kRead, kNone,
     "a fault is reported by its statusword and EMCY, without 0x603F"},
    {0x6040, 0, "controlword", dt::kUnsigned16, 0, kReadWrite, kRpdo},
    {0x6041, 0, "statusword", dt::kUnsigned16, 0, kRead, kTpdo},
    {0x6060, 0, "modes of operation", dt::kInteger8, 0, kReadWrite},
    {0x6061, 0, "modes of operation display", dt::kInteger8, 0, kRead},
    {0x6064, 0, "position actual value", dt::kInteger32, 0, kRead, kTpdo},
    {0x606C, 0, "velocity actual value", dt::kInteger32, 0, kRead, kTpdo},
    {0x607A, 0, "target position", dt::kInteger32, 0, kReadWrite},
    {0x6081, 0, "profile velocity", dt::kUnsigned32, 0, kReadWrite},
    {0x6083, 0, "profile acceleration", dt::kUnsigned32, 0, kReadWrite},
    {0x6084, 0, "profile deceleration", dt::kUnsigned32, 0, kReadWrite},
    {0x60F4, 0, "following error actual value", dt::kInteger32, 0, kRead, kTpdo,
     "no following-error channel; the following-error limit is not judged"},
    {0x60FF, 0, "target velocity", dt::kInteger32, 0, kReadWrite},
}));

}  // namespace

std::span<const UsedObject> Cia402Drive::used_objects() noexcept {
  return kDriveObjects;
}

Cia402Drive::Cia402Drive(SdoClient& sdo, Cia402Options options)
    : sdo_(sdo), options_(options), timer_(sdo.bus().context()) {}

void Cia402Drive::throw_if(const std::error_code& ec) const {
  if (!ec) return;
  if (ec.category() == cia402_category()) throw Cia402Error(failure_);
  throw SdoError(ec, sdo_.node(), kControlword, 0);
}

void Cia402Drive::sleep(std::chrono::milliseconds d) {
  // The flag is shared with the timer's handler: another handler's exception may leave this wait
  // (unchanged, to our caller) before the timer fires.
  auto done = std::make_shared<bool>(false);
  timer_.expires_after(d);
  timer_.async_wait([done](const boost::system::error_code&) { *done = true; });
  can::run_until(sdo_.bus().context(), [&done] { return *done; });
}

void Cia402Drive::fail(Cia402Errc errc, std::uint16_t sw, const std::string& what,
                       std::error_code& ec) {
  failure_ = {};
  failure_.code = errc;
  failure_.state = decode_state(sw);
  failure_.statusword = sw;
  std::error_code read_ec;
  failure_.error_code = sdo_.read<std::uint16_t>(kErrorCode, 0, read_ec);
  const std::string code_text =
      read_ec ? fmt::format("0x603F unreadable: {}", read_ec.message())
              : fmt::format("error code 0x603F = 0x{:04X}", failure_.error_code);
  failure_.message = fmt::format("CiA 402 node {}: {}: stuck in {}, {}", sdo_.node(), what,
                                 describe_statusword(sw), code_text);
  ec = errc;
}

std::uint16_t Cia402Drive::statusword(std::error_code& ec) {
  return sdo_.read<std::uint16_t>(kStatusword, 0, ec);
}

Cia402State Cia402Drive::state(std::error_code& ec) {
  const auto sw = statusword(ec);
  return ec ? Cia402State::unknown : decode_state(sw);
}

void Cia402Drive::write_controlword(std::uint16_t cw, std::error_code& ec) {
  sdo_.write<std::uint16_t>(kControlword, 0, cw, ec);
  if (!ec) controlword_ = cw;
}

void Cia402Drive::go_to(Cia402State target, std::error_code& ec) {
  ec.clear();
  failure_ = {};
  const auto deadline = std::chrono::steady_clock::now() + options_.state_timeout;
  int resets = 0;
  std::uint16_t sw = 0;
  // The state last commanded from, if any (a flag and a value: GCC 12 misreads an optional<enum>
  // in this loop as maybe-uninitialized once exceptions may leave it).
  bool commanded = false;
  Cia402State commanded_from = Cia402State::not_ready_to_switch_on;
  for (;;) {
    sw = statusword(ec);
    if (ec) return;
    const auto current = decode_state(sw);
    if (current == target) return;
    if (std::chrono::steady_clock::now() > deadline) {
      return fail(Cia402Errc::cannot_reach_state, sw,
                  fmt::format("cannot reach {}", to_string(target)), ec);
    }
    if (current == Cia402State::fault) {
      if (resets >= options_.max_fault_resets) {
        return fail(Cia402Errc::fault, sw, fmt::format("fault persists after {} resets", resets),
                    ec);
      }
      // Fault reset acts on the rising edge of bit 7: bit 7 low first, then high.
      write_controlword(controlword::disable_voltage, ec);
      if (ec) return;
      write_controlword(controlword::fault_reset, ec);
      if (ec) return;
      ++resets;
      commanded = true;
      commanded_from = current;
      // Give the drive time to leave fault before another edge.
      const auto settle = std::chrono::steady_clock::now() +
                          options_.state_timeout / (options_.max_fault_resets + 1);
      do {
        sleep(options_.poll_interval);
        sw = statusword(ec);
        if (ec) return;
      } while (decode_state(sw) == Cia402State::fault && std::chrono::steady_clock::now() < settle);
      continue;
    }
    const auto cw = controlword_toward(current, target);
    if (cw && (!commanded || commanded_from != current)) {
      // Keep the operation-mode bits (4-6, 8) of the last controlword; the command bits
      // select the transition.
      const auto mode_bits = static_cast<std::uint16_t>(controlword_ & 0x0170U);
      write_controlword(
          static_cast<std::uint16_t>(*cw | (*cw == controlword::enable_operation ? mode_bits : 0U)),
          ec);
      if (ec) return;
      commanded = true;
      commanded_from = current;
      continue;
    }
    sleep(options_.poll_interval);
    // Re-command after a poll with no progress: some drives ignore a write while busy.
    if (cw) commanded = false;
  }
}

void Cia402Drive::go_to(Cia402State target) {
  std::error_code ec;
  go_to(target, ec);
  throw_if(ec);
}

void Cia402Drive::quick_stop(std::error_code& ec) {
  ec.clear();
  auto sw = statusword(ec);
  if (ec) return;
  if (decode_state(sw) != Cia402State::operation_enabled) {
    // Quick stop from the other states means disable voltage (transitions 7, 10).
    return go_to(Cia402State::switch_on_disabled, ec);
  }
  write_controlword(controlword::quick_stop, ec);
  if (ec) return;
  // Depending on 0x605A the drive stays in quick stop active or goes on to switch on disabled.
  const auto deadline = std::chrono::steady_clock::now() + options_.state_timeout;
  for (;;) {
    sw = statusword(ec);
    if (ec) return;
    const auto st = decode_state(sw);
    if (st == Cia402State::quick_stop_active || st == Cia402State::switch_on_disabled) return;
    if (std::chrono::steady_clock::now() > deadline) {
      return fail(Cia402Errc::cannot_reach_state, sw, "quick stop not taken", ec);
    }
    sleep(options_.poll_interval);
  }
}

void Cia402Drive::quick_stop() {
  std::error_code ec;
  quick_stop(ec);
  throw_if(ec);
}

void Cia402Drive::fault_reset(std::error_code& ec) {
  ec.clear();
  auto sw = statusword(ec);
  if (ec || decode_state(sw) != Cia402State::fault) return;
  write_controlword(controlword::disable_voltage, ec);
  if (ec) return;
  write_controlword(controlword::fault_reset, ec);
  if (ec) return;
  const auto deadline = std::chrono::steady_clock::now() + options_.state_timeout;
  while (decode_state(sw) == Cia402State::fault) {
    if (std::chrono::steady_clock::now() > deadline) {
      return fail(Cia402Errc::fault, sw, "fault reset not accepted", ec);
    }
    sleep(options_.poll_interval);
    sw = statusword(ec);
    if (ec) return;
  }
}

void Cia402Drive::fault_reset() {
  std::error_code ec;
  fault_reset(ec);
  throw_if(ec);
}

void Cia402Drive::set_mode(OperationMode mode, std::error_code& ec) {
  ec.clear();
  sdo_.write<std::int8_t>(kModes, 0, static_cast<std::int8_t>(mode), ec);
  if (ec) return;
  const auto deadline = std::chrono::steady_clock::now() + options_.state_timeout;
  for (;;) {
    const auto shown = sdo_.read<std::int8_t>(kModesDisplay, 0, ec);
    if (ec) return;
    if (shown == static_cast<std::int8_t>(mode)) break;
    if (std::chrono::steady_clock::now() > deadline) {
      const auto sw = statusword(ec);
      if (ec) return;
      return fail(Cia402Errc::mode_not_accepted, sw,
                  fmt::format("mode {} ({}) not accepted, 0x6061 shows {}", to_string(mode),
                              static_cast<int>(mode), static_cast<int>(shown)),
                  ec);
    }
    sleep(options_.poll_interval);
  }
  mode_ = mode;
}

void Cia402Drive::set_mode(OperationMode mode) {
  std::error_code ec;
  set_mode(mode, ec);
  throw_if(ec);
}

void Cia402Drive::move(const ProfileMove& m, std::error_code& ec) {
  ec.clear();
  auto sw = statusword(ec);
  if (ec) return;
  if (decode_state(sw) != Cia402State::operation_enabled) {
    return fail(Cia402Errc::not_enabled, sw, "profile move refused", ec);
  }
  if (m.profile_velocity) sdo_.write<std::uint32_t>(kProfileVelocity, 0, *m.profile_velocity, ec);
  if (!ec && m.acceleration) sdo_.write<std::uint32_t>(kAcceleration, 0, *m.acceleration, ec);
  if (!ec && m.deceleration) sdo_.write<std::uint32_t>(kDeceleration, 0, *m.deceleration, ec);
  if (!ec) sdo_.write<std::int32_t>(kTargetPosition, 0, m.target, ec);
  if (ec) return;
  const auto base = static_cast<std::uint16_t>(
      controlword::enable_operation | (m.immediately ? controlword::change_immediately : 0U) |
      (m.relative ? controlword::relative : 0U));
  // A set-point acknowledge still high from the last move must drop before a new edge counts.
  write_controlword(base, ec);
  if (ec) return;
  write_controlword(static_cast<std::uint16_t>(base | controlword::new_set_point), ec);
  if (ec) return;
  const auto deadline = std::chrono::steady_clock::now() + options_.state_timeout;
  for (;;) {
    sw = statusword(ec);
    if (ec) return;
    if ((sw & statusword::bit12) != 0) break;
    if (decode_state(sw) != Cia402State::operation_enabled) {
      return fail(Cia402Errc::not_enabled, sw, "drive left operation enabled during a move", ec);
    }
    if (std::chrono::steady_clock::now() > deadline) {
      return fail(Cia402Errc::set_point_not_acknowledged, sw,
                  fmt::format("set-point {} not acknowledged (statusword bit 12)", m.target), ec);
    }
    sleep(options_.poll_interval);
  }
  write_controlword(base, ec);
}

void Cia402Drive::move(const ProfileMove& m) {
  std::error_code ec;
  move(m, ec);
  throw_if(ec);
}

void Cia402Drive::wait_target_reached(std::chrono::milliseconds timeout, std::error_code& ec) {
  ec.clear();
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const auto sw = statusword(ec);
    if (ec) return;
    const auto st = decode_state(sw);
    if (st != Cia402State::operation_enabled) {
      return fail(st == Cia402State::fault ? Cia402Errc::fault : Cia402Errc::not_enabled, sw,
                  "drive left operation enabled before the target", ec);
    }
    if (following_error_bit(sw, mode_)) {
      std::error_code fe_ec;
      const auto fe = following_error(fe_ec);
      return fail(
          Cia402Errc::following_error, sw,
          fe_ec ? std::string("following error") : fmt::format("following error {} (0x60F4)", fe),
          ec);
    }
    if ((sw & statusword::target_reached) != 0 && (sw & statusword::bit12) == 0) return;
    if ((sw & statusword::target_reached) != 0 && mode_ != OperationMode::profile_position) return;
    if (std::chrono::steady_clock::now() > deadline) {
      return fail(Cia402Errc::target_not_reached, sw, "target not reached", ec);
    }
    sleep(options_.poll_interval);
  }
}

void Cia402Drive::wait_target_reached(std::chrono::milliseconds timeout) {
  std::error_code ec;
  wait_target_reached(timeout, ec);
  throw_if(ec);
}

void Cia402Drive::set_target_velocity(std::int32_t velocity, std::error_code& ec) {
  sdo_.write<std::int32_t>(kTargetVelocity, 0, velocity, ec);
}

void Cia402Drive::set_target_velocity(std::int32_t velocity) {
  sdo_.write<std::int32_t>(kTargetVelocity, 0, velocity);
}

void Cia402Drive::set_target_position(std::int32_t position, std::error_code& ec) {
  sdo_.write<std::int32_t>(kTargetPosition, 0, position, ec);
}

void Cia402Drive::set_target_position(std::int32_t position) {
  sdo_.write<std::int32_t>(kTargetPosition, 0, position);
}

std::int32_t Cia402Drive::following_error(std::error_code& ec) {
  return sdo_.read<std::int32_t>(kFollowingError, 0, ec);
}

std::uint16_t Cia402Drive::error_code(std::error_code& ec) {
  return sdo_.read<std::uint16_t>(kErrorCode, 0, ec);
}

}  // namespace wavebench::canopen
