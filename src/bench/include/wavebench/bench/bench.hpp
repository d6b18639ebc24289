#pragma once
// The daemon's view of a bench (bench.md §1, §7), after ros2_control's hardware interfaces: an
// abstract bench with a lifecycle and an error state, not copyable, that procedures drive with
// blocking calls and that hands every assembled SYNC sample to its observers.
//
// Threads: one bench thread owns the bench. Every call below except request_stop(),
// state(), fault_reason() and description() is made on it. Blocking calls run the bench's event
// loop while they wait, so SYNC, PDOs, acquisition, heartbeats and safety keep working during
// a move or a wait. Observers are called on the bench thread and must not block (the twin
// copies the sample into its own queue).
//
// Time: now() is bench time in seconds since connect(). On a real bench it follows the steady
// clock. On the simulated clock (BenchDescription::simulated_clock) bench time is
// SYNC index × SYNC period and SYNCs are produced as fast as the simulated devices answer, so a
// run takes a fraction of its real duration; waits and timeouts given here are in bench time.
//
// Power (after ros2_control's inactive/active): a connected bench is inactive, i.e. the devices
// are configured, SYNC, PDOs and heartbeats flow and every channel is readable, but the drive's
// power stage is off (Switch On Disabled or Ready To Switch On) and the brake output is off.
// The first motion command of a run (or activate()) enables the drive; deactivate(), which the
// run executor calls when a run ends however it ends, switches it off again.
//
// Safety: a safety trigger (heartbeat lost, EMCY, Modbus link lost past its timeout, a limit
// crossed, request_stop) puts the bench in its safe state at once (brake output to its safe
// value, servo quick stop), moves the lifecycle to kFault with the reason, and makes the
// blocking call in progress (and every later motion call) throw BenchAborted. Samples acquired
// up to then have already gone to the observers.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavebench/bench/bench_description.hpp"
#include "wavebench/bench/bench_lifecycle.hpp"
#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::bench {

// Thrown by a blocking call when the bench has tripped; what() is the reason.
class BenchAborted : public std::runtime_error {
 public:
  explicit BenchAborted(const std::string& reason) : std::runtime_error(reason) {}
};

class SampleObserver {
 public:
  virtual ~SampleObserver() = default;
  // Called once per SYNC cycle with the sample as assembled (flags tell missing channels).
  virtual void on_sample(const storage::SyncSample& sample) noexcept = 0;
};

struct AcquisitionStats {
  std::uint64_t syncs_sent = 0;
  std::uint64_t samples = 0;             // samples handed to observers
  std::uint64_t incomplete_samples = 0;  // a channel missing
  std::uint64_t sync_late = 0;           // SYNC producer woke late (real clock only)
  std::uint64_t sync_skipped = 0;        // whole periods skipped (real clock only)
  double bus_load = 0;                   // estimated fraction of the bus bit rate
  // Added for the benchmark (jitter) and the gap report:
  std::uint64_t cycles_timed_out = 0;  // simulated clock: a cycle closed by its real-time timeout
  std::uint64_t late_frames = 0;       // a cycle's PDO that arrived after the cycle closed
  double sync_lateness_p50_s = 0;      // SYNC sent after its deadline (real clock only)
  double sync_lateness_p99_s = 0;
  double sync_lateness_max_s = 0;
  double bench_time_s = 0;  // now()
  double real_time_s = 0;   // steady clock since connect()
  // Heartbeats of the servo drive as the bench thread processed them, and the largest real-time
  // gap between two of them: how long the event loop left them unread at worst.
  std::uint64_t drive_heartbeats = 0;
  double drive_heartbeat_gap_max_s = 0;
  // The safe state as last seen, so that an idle bench shows it (issue #9): the drive's last
  // statusword (TPDO1) and its CiA 402 state's name, the brake controller's output bit (status
  // register read back); unset when none arrived recently.
  std::optional<std::uint16_t> drive_statusword;
  std::string drive_state;
  std::optional<bool> brake_output_on;
  // The brake controller's readback beside it (bench panel): coil temperature, raw status
  // word, and the decoded alarm (empty without one).
  std::optional<double> brake_coil_temperature_c;
  std::optional<std::uint16_t> brake_status_word;
  std::string brake_alarm;
  // Each CANopen node as its heartbeats (or node-guarding answers) show it: NMT state of the
  // last one ("" before the first), wall time since it (-1 before the first), how many
  // arrived, and how the node is supervised.
  struct NodeHeartbeat {
    std::uint8_t node = 0;
    std::string nmt_state;
    double heartbeat_age_s = -1;
    std::uint64_t heartbeats = 0;
    std::string supervision = "heartbeat";  // or "node guarding"
  };
  std::vector<NodeHeartbeat> nodes;
  // Simulated clock: cycles whose next SYNC waited for a device slower than the configured
  // rate, the longest wait [s], and those devices.
  std::uint64_t cycles_waited_for_devices = 0;
  double longest_device_wait_s = 0;
  std::vector<std::string> late_devices;
};

// A device of the bench as the API lists it: its name, its CANopen node (none for the Modbus
// brake), the channels it writes (state interfaces) and the set-points it takes (command
// interfaces).
struct BenchDeviceInfo {
  std::string name;
  std::optional<std::uint8_t> node;
  std::vector<storage::ChannelInfo> channels;
  std::vector<storage::ChannelInfo> commands;
};

class Bench {
 public:
  Bench() = default;
  virtual ~Bench() = default;
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  virtual const BenchDescription& description() const noexcept = 0;
  // The channels beyond the six core ones, in SyncSample::extra order (the config's devices).
  virtual std::vector<storage::ChannelInfo> extra_channels() const { return {}; }
  // Its devices, in the order the bench configures them. (The default: none described.)
  virtual std::vector<BenchDeviceInfo> device_info() const { return {}; }

  // Boots the nodes (NMT), configures PDOs by SDO, arms heartbeat consumers, starts SYNC and
  // acquisition, connects the brake (output off) and leaves the drive disabled (Switch On
  // Disabled): kUnconfigured -> kInactive. Throws std::runtime_error naming the device
  // and what failed.
  virtual void connect() = 0;
  // A clean exit: brake output off, the brake controller's watchdog switched off (so a real
  // controller does not latch its watchdog alarm), drive to Switch On Disabled, SYNC stopped,
  // nodes to pre-operational. Never throws.
  virtual void disconnect() noexcept = 0;
  virtual BenchLifecycle state() const noexcept = 0;
  virtual std::string fault_reason() const = 0;
  // kFault -> kInactive: brake alarm reset (output off), drive fault reset to Switch On
  // Disabled (never enabled here). Throws when the cause persists (e.g. heartbeat still
  // missing).
  virtual void clear_fault() = 0;
  // kInactive -> kActive: enables the drive (Operation Enabled) for motion; motion commands and
  // a brake torque above 0 call it on their own. Throws like a motion command.
  virtual void activate() {}
  // kActive -> kInactive: brake output off, drive power stage off (Ready To Switch On; Switch
  // On Disabled after a trip, a drive in fault left in fault), the bench still connected and
  // acquiring. Never throws.
  virtual void deactivate() noexcept {}

  // Profile-position move of the input (motor) shaft to an absolute angle [rad, unwrapped],
  // at `speed` [rad/s of the input]; returns when the drive reports target reached.
  virtual void move_input_to(double theta_in_rad, double speed_rad_s) = 0;
  // Profile-velocity run of the input shaft [rad/s, signed]; returns once commanded.
  virtual void run_input_velocity(double omega_in_rad_s) = 0;
  // Velocity to zero and wait until the input stands still.
  virtual void stop_motion() = 0;
  // Brake torque setpoint [N·m, >= 0] with a ramp [N·m/s, 0 = step]; returns once commanded.
  virtual void set_brake_torque(double torque_nm, double ramp_nm_per_s = 0) = 0;
  // Runs the bench for `seconds` of bench time.
  virtual void wait_for(double seconds) = 0;
  // Runs the bench until `done()` (checked after every sample) or `timeout_s` of bench time;
  // returns whether done() became true.
  virtual bool wait_until(const std::function<bool()>& done, double timeout_s) = 0;
  virtual double now() const = 0;
  // Runs the event loop for `seconds` of bench time in any state without moving anything and
  // without throwing BenchAborted: keeps heartbeats, the brake and acquisition serviced while
  // the daemon is idle or in fault. (Added; the default does nothing.)
  virtual void idle_for(double seconds) { (void)seconds; }
  // The last assembled sample (all zero before the first).
  virtual const storage::SyncSample& latest_sample() const = 0;

  virtual void add_observer(SampleObserver& observer) = 0;
  virtual void remove_observer(SampleObserver& observer) = 0;
  virtual AcquisitionStats acquisition_stats() const = 0;
  // Channels the connected bench goes without because a device lacks an optional object
  // (e.g. "drive.following_error" when the drive answers 0x60F4 with SDO abort 06020000); the
  // connect log gives the reasons. (Added; the default has none.)
  virtual std::vector<std::string> absent_channels() const { return {}; }

  // Operator stop, from any thread: trips the bench with `reason` (see Safety above).
  virtual void request_stop(const std::string& reason) noexcept = 0;
};

}  // namespace wavebench::bench
