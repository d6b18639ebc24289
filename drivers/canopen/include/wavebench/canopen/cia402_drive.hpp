#pragma once
// A CiA 402 drive driven by SDO: walks the state machine (fault reset on a rising edge of bit 7),
// selects modes (PP with the new-set-point handshake, PV, CSV, CSP), and when it cannot reach a
// state it says why: the state it is stuck in, the statusword, and the error code 0x603F.
// Blocking calls wait in the one event loop (see SdoClient); each comes throwing (Cia402Error)
// and with std::error_code&, after which last_failure() holds the explanation.

#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>

#include "wavebench/canopen/cia402.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::canopen {

enum class Cia402Errc {
  cannot_reach_state = 1,  // stuck: the drive did not follow the controlword
  fault,                   // in fault and the reset did not clear it
  mode_not_accepted,       // 0x6061 does not echo 0x6060
  set_point_not_acknowledged,
  following_error,
  not_enabled,  // a motion command while not in operation enabled
  target_not_reached,
};
const std::error_category& cia402_category() noexcept;
std::error_code make_error_code(Cia402Errc e) noexcept;

struct Cia402Failure {
  std::error_code code;
  Cia402State state = Cia402State::unknown;
  std::uint16_t statusword = 0;
  std::uint16_t error_code = 0;  // 0x603F when it could be read
  std::string message;
};

class Cia402Error : public std::system_error {
 public:
  explicit Cia402Error(const Cia402Failure& failure)
      : std::system_error(failure.code, failure.message), failure_(failure) {}
  const Cia402Failure& failure() const noexcept { return failure_; }

 private:
  Cia402Failure failure_;
};

struct Cia402Options {
  std::chrono::milliseconds state_timeout{2000};  // per requested state change
  std::chrono::milliseconds poll_interval{2};
  int max_fault_resets = 3;
};

struct ProfileMove {
  std::int32_t target = 0;                        // 0x607A, position units
  std::optional<std::uint32_t> profile_velocity;  // 0x6081
  std::optional<std::uint32_t> acceleration;      // 0x6083
  std::optional<std::uint32_t> deceleration;      // 0x6084
  bool relative = false;
  bool immediately = true;
};

class Cia402Drive {
 public:
  explicit Cia402Drive(SdoClient& sdo, Cia402Options options = {});
  Cia402Drive(const Cia402Drive&) = delete;
  Cia402Drive& operator=(const Cia402Drive&) = delete;

  // Every object the bench uses on a CiA 402 drive (SDO and its TPDO1/TPDO2 mapping).
  static std::span<const UsedObject> used_objects() noexcept;

  SdoClient& sdo() noexcept { return sdo_; }
  const Cia402Failure& last_failure() const noexcept { return failure_; }

  std::uint16_t statusword(std::error_code& ec);
  Cia402State state(std::error_code& ec);
  void write_controlword(std::uint16_t cw, std::error_code& ec);
  std::uint16_t last_controlword() const noexcept { return controlword_; }

  // Walks the state machine to `target`, resetting faults on the way.
  void go_to(Cia402State target);
  void go_to(Cia402State target, std::error_code& ec);
  void enable_operation() { go_to(Cia402State::operation_enabled); }
  void enable_operation(std::error_code& ec) { go_to(Cia402State::operation_enabled, ec); }
  void disable_voltage(std::error_code& ec) { go_to(Cia402State::switch_on_disabled, ec); }
  // Transition 11: operation enabled -> quick stop active.
  void quick_stop();
  void quick_stop(std::error_code& ec);
  // Transition 15 alone: a rising edge of bit 7, then wait to leave fault.
  void fault_reset();
  void fault_reset(std::error_code& ec);

  void set_mode(OperationMode mode);
  void set_mode(OperationMode mode, std::error_code& ec);

  // PP: set-point, new-set-point bit, wait for the acknowledge (bit 12), release bit 4.
  void move(const ProfileMove& move);
  void move(const ProfileMove& move, std::error_code& ec);
  // Waits for target reached (bit 10); following error (bit 13) or fault fail it.
  void wait_target_reached(std::chrono::milliseconds timeout);
  void wait_target_reached(std::chrono::milliseconds timeout, std::error_code& ec);
  // PV / CSV target velocity 0x60FF; CSP target position 0x607A (acyclic: by SDO).
  void set_target_velocity(std::int32_t velocity);
  void set_target_velocity(std::int32_t velocity, std::error_code& ec);
  void set_target_position(std::int32_t position);
  void set_target_position(std::int32_t position, std::error_code& ec);
  // Following error actual 0x60F4; a statusword bit 13 in PP/CSP is reported as an error.
  std::int32_t following_error(std::error_code& ec);
  std::uint16_t error_code(std::error_code& ec);  // 0x603F

 private:
  void fail(Cia402Errc errc, std::uint16_t sw, const std::string& what, std::error_code& ec);
  void sleep(std::chrono::milliseconds d);
  void throw_if(const std::error_code& ec) const;

  SdoClient& sdo_;
  Cia402Options options_;
  boost::asio::steady_timer timer_;
  std::uint16_t controlword_ = 0;
  std::optional<OperationMode> mode_;
  Cia402Failure failure_;
};

}  // namespace wavebench::canopen

template <>
struct std::is_error_code_enum<wavebench::canopen::Cia402Errc> : std::true_type {};
