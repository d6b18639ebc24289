#pragma once
// Manual control of the bench from the console's manual panel (issue #21): jog the input
// (hold-to-run), go to an output angle, set a brake torque, servo on/off.
//
// Threads: the API threads ask (jog, stop, go_to, brake, servo, keep_alive); the bench thread
// acts, in serve(), between slices of its idle event loop. Nothing here calls the bench from an
// API thread: a request only changes what is wanted, and wakes the bench thread.
//
// Dead-man (why: a page that stops talking must not leave a shaft turning): a jog lasts while
// the page repeats it; kJogTimeout after the last repeat the bench thread stops the input. A
// servo switched on and held (or loaded by the brake) stays on while the page keeps the session
// alive; kHoldTimeout after the last keep-alive it goes off (inactive: drive disabled, brake
// off). A go-to is one blocking move: an explicit stop or a lost keep-alive during it trips the
// bench (the only way to interrupt a profile move), which leaves the safe state.
//
// Power: the lifecycle is active only while the panel moves or holds something; servo off is
// inactive. A jog with the servo off switches it on for the jog and off again after.

#include <chrono>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "wavebench/bench/bench.hpp"

namespace wavebench::daemon {

struct ManualLimits {
  // The panel's own bound on the input speed (jog and go-to), below the bench's safety limit
  // whatever this says: slow enough to mount a unit by hand.
  double max_speed_rpm = 60;
  // A go-to's angle is within the output's turn, ±this [deg]; it moves the shorter way there.
  double max_move_deg = 360;
};

// What the panel is doing, for /api/status and the servo's words.
struct ManualState {
  bool servo_on = false;           // the panel holds the servo on (asked, or for a jog)
  double jog_rpm = 0;              // the jog being run (signed, input side); 0: none
  std::optional<double> goto_deg;  // the output angle being gone to
  double brake_nm = 0;             // the brake torque the panel set
  std::string last_stop;           // why manual control last ended (empty: never)
  double max_speed_rpm = 0;        // the effective bound: min(setting, safety limit)
  double max_brake_torque_nm = 0;  // 0: the panel cannot load the brake
  double jog_timeout_s = 0;        // keep-alive silence that stops a jog
  double stop_within_s = 0;        // ... and the bound on the input standing after it
  double hold_timeout_s = 0;
};

// A request refused before anything moves: the HTTP status and the text naming the key, the
// value and what was expected.
struct ManualRefusal {
  int status = 400;
  std::string detail;
};

class ManualSession {
 public:
  using Clock = std::chrono::steady_clock;
  // The jog's keep-alive silence after which the bench thread stops the input, and the bound
  // it guarantees on the input standing, counted from the last keep-alive the page sent: the
  // silence, the request's own way to the daemon, one serve slice and the drive's ramp down
  // (20 ms from 60 rpm at the simulated drive's 50 rev/s²); measured about 400 ms on a loaded
  // test machine. The page repeats every 100 ms: two repeats may be lost or late.
  static constexpr auto kJogTimeout = std::chrono::milliseconds(300);
  static constexpr auto kStopBound = std::chrono::milliseconds(500);
  static constexpr auto kHoldTimeout = std::chrono::seconds(5);
  // How often the bench thread serves the session while it is engaged.
  static constexpr auto kServeSlice = std::chrono::milliseconds(20);

  // `wake` makes the bench thread call serve() soon (it is idle, between slices).
  explicit ManualSession(std::function<void()> wake, ManualLimits limits = {});

  // Once the bench is built (its safety limits and gear sense bound every request).
  void set_bench(const bench::BenchDescription& description);

  // API threads. Each returns a refusal or nothing; nothing moves on a refusal.
  // `speed_rpm` is signed (the direction); repeating it is the jog's keep-alive.
  std::optional<ManualRefusal> jog(double speed_rpm);
  // Ends a jog (or a held servo's motion). Returns true when a go-to is in progress: the
  // caller then trips the bench, the only way to interrupt it.
  bool stop(const std::string& why);
  std::optional<ManualRefusal> go_to(double angle_deg, double speed_rpm);
  std::optional<ManualRefusal> brake(double torque_nm);
  void servo(bool on);
  void keep_alive();
  // Whether the panel holds the servo or is about to: a run is refused then.
  bool engaged() const;
  ManualState state() const;

  // Bench thread, between idle slices: applies what is wanted, enforces the dead-man, and
  // ends manual control (safe) when the bench has tripped. Never throws.
  void serve(bench::Bench& bench) noexcept;

 private:
  struct Wanted {
    bool servo_on = false;  // asked for explicitly
    double jog_rpm = 0;
    Clock::time_point jog_deadline{};
    std::optional<double> goto_deg;  // a go-to asked for and not yet begun
    double goto_speed_rpm = 0;
    double brake_nm = 0;
    Clock::time_point alive_deadline{};  // motion (a go-to) needs keep-alives until then
    Clock::time_point hold_deadline{};   // a held servo or brake, until then
  };
  struct Applied {
    bool powered = false;  // the panel activated the bench
    double jog_rpm = 0;
    double brake_nm = 0;
  };

  std::optional<ManualRefusal> check_speed(const char* key, double speed_rpm, bool signed_ok) const;
  void end_all(bench::Bench& bench, const std::string& why) noexcept;
  void do_go_to(bench::Bench& bench, double angle_deg, double speed_rpm);
  class GoToWatch;

  std::function<void()> wake_;
  ManualLimits limits_;
  mutable std::mutex mutex_;
  std::optional<bench::BenchDescription> description_;
  Wanted wanted_;
  std::optional<double> going_deg_;  // a go-to in progress on the bench thread
  Applied applied_;                  // bench thread only, copied into `shown_` under mutex_
  Applied shown_;
  std::string last_stop_;
};

}  // namespace wavebench::daemon
