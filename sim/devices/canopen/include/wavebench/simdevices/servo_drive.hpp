#pragma once
// The simulated CiA 402 servo drive (node 1 by default): the power drive state machine, modes
// PP (new-set-point handshake, change immediately, relative, halt, target reached), PV, CSP
// and CSV, a cascaded position (P) -> velocity (PI) -> torque loop with speed and torque
// limits, following-error supervision, software position limits, and fault injection with
// EMCY, and the abort connection option (0x6007) on entering NMT stopped. Inside, positions
// are motor encoder increments, velocities increments/s, accelerations increments/s^2; on the
// bus they are in the drive's units (ServoDriveConfig::velocity_unit). Torque is per mille of
// the rated torque (0x6076).

#include <cstdint>
#include <vector>

#include "wavebench/model/pi_controller.hpp"
#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/simdevices/canopen_node.hpp"
#include "wavebench/simdevices/cia402_state_machine.hpp"
#include "wavebench/simdevices/motion_profile.hpp"

namespace wavebench::simdevices {

// The units of the drive's position, velocity and acceleration objects (issue #9).
enum class DriveVelocityUnit {
  kCounts,       // increments, increments/s, increments/s^2
  kRpm,          // increments, rpm, rpm/s
  kDeciRpm,      // increments, 0.1 rpm, 0.1 rpm/s
  kFactorGroup,  // user units of the factor group 0x608F..0x6092: feed constant per driving
                 // shaft revolution, a driving shaft revolution being gear ratio motor revs;
                 // velocity in them per s, acceleration per s^2 (no 0x60A8/0x60A9 objects)
};

// Numerator / denominator of the factor group objects (sub-indices 1 and 2).
struct DriveFactorGroupConfig {
  std::uint32_t position_encoder_increments = 131072;  // 0x608F
  std::uint32_t position_encoder_revolutions = 1;
  std::uint32_t velocity_encoder_increments = 131072;  // 0x6090 (per s)
  std::uint32_t velocity_encoder_revolutions = 1;      // (per s)
  std::uint32_t gear_motor_revolutions = 1;            // 0x6091
  std::uint32_t gear_shaft_revolutions = 1;
  std::uint32_t feed = 131072;  // 0x6092
  std::uint32_t feed_shaft_revolutions = 1;
};

// Object units per internal unit: what the bus sees of an increment, increment/s, increment/s^2.
struct DriveObjectUnits {
  double position = 1;
  double velocity = 1;
  double acceleration = 1;
};

struct ServoDriveConfig {
  std::uint8_t node_id = 1;
  NodeIdentity identity{0x00020192, "WB-SIM servo drive", "1.0",      "wavebench-sim 0.1",
                        0x00000A57, 0x00000402,           0x00010000, 0x00001001};
  std::uint32_t counts_per_revolution = 131072;          // 0x608F:01 over 0x608F:02 = 1 motor rev
  double rated_torque_nm = 1.3;                          // 0x6076 (stored in mN*m)
  std::uint16_t max_torque_permille = 3000;              // 0x6072
  std::uint32_t max_motor_speed_rpm = 3000;              // 0x6080
  double position_gain = 120;                            // [1/s]
  double velocity_gain = 0.08;                           // [N*m*s/rad]
  double velocity_integral_time = 0.01;                  // [s], 0 = P only
  double control_period = 250e-6;                        // [s] servo loop period
  std::uint32_t profile_velocity = 131072 * 10;          // 0x6081 [inc/s]
  std::uint32_t profile_acceleration = 131072 * 50;      // 0x6083 [inc/s^2]
  std::uint32_t profile_deceleration = 131072 * 50;      // 0x6084
  std::uint32_t quick_stop_deceleration = 131072 * 200;  // 0x6085
  std::int16_t quick_stop_option = 6;  // 0x605A: 2 -> switch on disabled after the stop, 6 stay
  // 0x6007 abort connection option code, applied when the node enters NMT stopped: 0 nothing,
  // 1 fault (0x8130), 2 disable voltage (power stage off at once), 3 quick stop. A real drive's
  // factory value varies; the bench writes 2 at configuration.
  std::int16_t abort_connection_option = 2;
  std::uint32_t following_error_window = 65536;   // 0x6065 [inc]
  std::uint16_t following_error_timeout_ms = 50;  // 0x6066
  std::uint32_t position_window = 20;             // 0x6067 [inc]
  std::uint16_t position_window_time_ms = 5;      // 0x6068
  std::uint16_t velocity_window = 200;            // 0x606D [inc/s]
  std::uint16_t velocity_window_time_ms = 5;      // 0x606E
  std::uint16_t velocity_threshold = 100;         // 0x606F [inc/s] "speed = 0"
  bool following_error_is_fault = true;           // error 0x8611 when the window is exceeded
  DriveVelocityUnit velocity_unit = DriveVelocityUnit::kCounts;
  DriveFactorGroupConfig factor_group;  // with kFactorGroup
  // SI unit objects 0x60A8 (position: increments) and 0x60A9 (velocity: increments/s, rev/min
  // or 0.1 rev/min as velocity_unit), a drive that states its units (issue #20). Off by default:
  // the shipped EDS has neither. Not with kFactorGroup (its user units have no SI name here).
  bool si_unit_objects = false;
  // Optional objects this drive model lacks (0x60F4, 0x6077, 0x603F): SDO access and PDO mapping
  // answer 06020000.
  std::vector<std::uint16_t> absent_objects;
  // TPDOs a master cannot remap (read-only parameters, issue 20), e.g. TPDO1 [0x6064, 0x6041].
  // The RPDOs stay writable: the bench maps RPDO1 with the controlword for its quick stop.
  std::vector<FixedTpdo> fixed_tpdos;

  bool has(std::uint16_t index) const;
  DriveObjectUnits object_units() const;
};

// Operation modes (0x6060) the drive accepts.
enum class Cia402Mode : std::int8_t {
  kNone = 0,
  kProfilePosition = 1,
  kProfileVelocity = 3,
  kCyclicSyncPosition = 8,
  kCyclicSyncVelocity = 9,
};

// 0x2F00: writing a non-zero error code injects that fault (tests, the CLI); manufacturer area.
inline constexpr std::uint16_t kFaultInjectionIndex = 0x2F00;

class Cia402ServoDrive final : public CanopenNode {
 public:
  Cia402ServoDrive(const ServoDriveConfig& config, FrameSink sink);

  // One servo period: reads the motor shaft from the plant, returns the motor torque [N*m].
  double control(const PlantState& plant, double dt);
  // Latches the position and speed feedback (0x6064, 0x606C) at the plant's present state, so
  // that a TPDO sent on SYNC carries the input angle of the same instant as the output encoder's
  // (devices latch on SYNC), not the one of the last control period's start.
  void observe(const PlantState& plant);
  // A fault with the given CiA 402 error code (0x603F): fault reaction, EMCY.
  void inject_fault(std::uint16_t error_code);

  Cia402State state() const noexcept { return machine_.state(); }
  std::uint16_t statusword() const;
  double counts_per_radian() const noexcept;
  const ServoDriveConfig& config() const noexcept { return config_; }

 protected:
  void on_sync(double now) override;
  void on_reset_application() override;
  void on_nmt_stopped() override;

 private:
  void add_profile_objects();
  void on_controlword();
  void on_mode_change();
  void start_new_set_point(std::uint16_t controlword);
  void update_outputs(const PlantState& plant);
  void update_target_reached(double position, double velocity, double dt);
  double motion_demand(double dt, double& velocity_ff);
  double clamp_to_software_limits(double position);
  std::uint16_t mode_bits() const;
  // Bus objects in the drive's units to and from increments (per s, per s^2).
  double position_in(double object_value) const { return object_value / units_.position; }
  double velocity_in(double object_value) const { return object_value / units_.velocity; }
  double acceleration_in(double object_value) const { return object_value / units_.acceleration; }
  std::int32_t position_out(double increments) const;
  std::int32_t velocity_out(double increments_per_s) const;

  ServoDriveConfig config_;
  DriveObjectUnits units_;
  model::PiController position_loop_;  // P: position error [inc] -> velocity [inc/s]
  model::PiController velocity_loop_;  // PI: speed error [rad/s] -> torque [N*m]
  Cia402StateMachine machine_;
  MotionProfile profile_;
  Cia402Mode active_mode_ = Cia402Mode::kNone;
  std::uint16_t last_controlword_ = 0;

  double actual_position_ = 0;  // [inc], unwrapped
  double actual_velocity_ = 0;  // [inc/s]
  double torque_ = 0;           // [N*m] last command
  bool limit_active_ = false;

  // Profile position
  double pp_target_ = 0;
  bool pp_buffered_ = false;
  double pp_buffered_target_ = 0;
  bool set_point_ack_ = false;
  bool profile_done_ = true;
  bool target_reached_ = true;
  double in_window_time_ = 0;

  // Cyclic synchronous position: linear interpolation between SYNC targets
  double csp_from_ = 0;
  double csp_to_ = 0;
  double csp_elapsed_ = 0;
  double csp_period_ = 1e-3;
  double last_sync_ = -1;

  bool following_error_ = false;
  double following_error_time_ = 0;
};

}  // namespace wavebench::simdevices
