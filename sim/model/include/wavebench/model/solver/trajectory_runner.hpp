#pragma once
// Drives an Integrator over [t0, t_end]: locates witness sign changes on the dense output and
// restarts the integrator there (no step straddles a kink), and samples the solution at a fixed
// rate from the dense output (so a spectrum sees no step-size jitter).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "wavebench/model/solver/integrator.hpp"
#include "wavebench/model/solver/ode_system.hpp"

namespace wavebench::model::solver {

struct TrajectoryOptions {
  double t_end = 1.0;
  double initial_step = 0;  // [s] 0 = the integrator chooses
  double sample_rate = 0;   // [Hz] 0 = no sampling
  double sample_t0 = 0;     // samples at exactly sample_t0 + k / sample_rate, k >= 0
  bool locate_events = true;
  double event_tolerance = 1e-12;  // [s] width of the bracket a located root lies in
  // Zeno guard: a crossing of the same witness closer than this to its previous event is not
  // fired again (counted in suppressed_events).
  double min_event_separation = 1e-10;  // [s]
  // Witnesses are also checked at this many evenly spaced points inside each step, so a
  // witness that crosses and recrosses within one step (a short contact) is not missed.
  int witness_probes = 1;
  std::int64_t max_steps = 100'000'000;  // accepted steps before run() gives up and throws
  double progress_interval = 0.01;       // fraction of [t0, t_end] between progress calls
};

struct EventRecord {
  double t = 0;  // first time the witness has its new sign (within event_tolerance)
  std::size_t witness = 0;
  int direction = 0;  // +1: g went from negative to positive, -1: the other way
};

struct TrajectoryResult {
  IntegratorCounters counters;  // this run only
  std::vector<EventRecord> events;
  std::int64_t samples = 0;
  std::int64_t suppressed_events = 0;
  std::int64_t root_iterations = 0;
  double t_final = 0;
};

class TrajectoryRunner {
 public:
  using SampleFn =
      std::function<void(double t, std::span<const double> y, std::span<const double> d)>;
  using ProgressFn = std::function<void(double fraction)>;

  // Throws std::invalid_argument naming an option that is out of range.
  TrajectoryRunner(Integrator& integrator, const OdeSystem& system, TrajectoryOptions options);
  TrajectoryRunner(const TrajectoryRunner&) = delete;
  TrajectoryRunner& operator=(const TrajectoryRunner&) = delete;

  void on_sample(SampleFn fn) { sample_ = std::move(fn); }
  void on_progress(ProgressFn fn) { progress_ = std::move(fn); }

  // y: the initial state in, the state at t_end out. d: the discrete state, which events change
  // in place (the integrator reads it through the span). Throws std::runtime_error when
  // max_steps accepted steps do not reach t_end.
  TrajectoryResult run(double t0, std::span<double> y, std::span<double> d);

 private:
  // Earliest sign change of witness k inside [a, b] on the dense output (Illinois).
  double locate_root(std::size_t k, double a, double ga, double b, double gb,
                     std::span<const double> d, TrajectoryResult& result);
  // Locates the first sign change of each witness over the last step (root_t_,
  // root_direction_) and returns the earliest root not suppressed by the Zeno guard.
  double find_crossings(double t_prev, double t, std::span<const double> d,
                        TrajectoryResult& result);
  void emit_samples_up_to(double t, std::span<const double> d, TrajectoryResult& result);

  Integrator& integrator_;
  const OdeSystem& system_;
  TrajectoryOptions options_;
  SampleFn sample_;
  ProgressFn progress_;
  std::int64_t next_sample_ = 0;
  std::vector<double> y_dense_, g_prev_, g_new_, g_probe_, last_event_t_, root_t_, probe_t_,
      probe_g_;
  std::vector<int> root_direction_;
};

}  // namespace wavebench::model::solver
