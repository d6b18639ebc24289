#pragma once
// Running the gear model: options in, sampled channels and solver statistics out.
// This is the contract between the model (sim/model) and its users (analysis, CLI, twin).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

enum class SolverMethod {
  kDormandPrince45,  // adaptive, dense output (default)
  kRk4,              // fixed step
  kRosenbrock4,      // stiff (LuGre with large sigma0)
};

struct SimulationOptions {
  double t_end = 1.0;          // [s]
  double transient = 0.0;      // [s] samples before this are not returned
  double sample_rate = 10000;  // [Hz] output from dense output at a fixed rate
  SolverMethod method = SolverMethod::kDormandPrince45;
  double rtol = 1e-6;
  double atol = 1e-9;         // scaled per state by the model's characteristic sizes
  double fixed_step = 1e-5;   // [s] RK4 step
  double max_step = 0;        // [s] 0 = no limit
  bool locate_events = true;  // backlash contact events, hysteresis reversals
  // Called now and then with the fraction done; long runs show progress through it.
  std::function<void(double fraction)> progress;
};

// Channels sampled at sample_rate after the transient. Angles relative to the nominal motion
// where named so; TE = theta2 - theta1/N at the output (model.md §1), in rad.
struct SampledResponse {
  std::vector<double> t;
  std::vector<double> theta1;        // input angle [rad] (absolute)
  std::vector<double> omega1;        // input speed [rad/s]
  std::vector<double> theta2_dev;    // theta2 - theta1_nominal(t)/N [rad]
  std::vector<double> omega2;        // output speed [rad/s]
  std::vector<double> alpha2;        // output angular acceleration [rad/s^2]
  std::vector<double> twist;         // Delta = theta1/N - theta2 - e [rad]
  std::vector<double> twist_rate;    // Delta' [rad/s]
  std::vector<double> te;            // theta2 - theta1/N [rad]
  std::vector<double> gear_torque;   // T_g at the output [N*m]
  std::vector<double> load_torque;   // T_L (brake or prescribed) [N*m]
  std::vector<double> motor_torque;  // T_m [N*m]
};

struct SolverStats {
  std::int64_t steps = 0;
  std::int64_t rejected_steps = 0;
  std::int64_t rhs_evaluations = 0;
  std::int64_t jacobian_evaluations = 0;
  std::int64_t events = 0;  // located contact / reversal events
  double wall_s = 0;
};

struct ContactEvent {
  double t = 0;
  std::string kind;  // "contact_lost", "contact_made", "reversal"
};

struct SimulationResult {
  SampledResponse response;
  SolverStats stats;
  std::vector<ContactEvent> events;
  double dissipated_energy_j = 0;  // integrated mesh + hysteresis + friction losses
};

SimulationResult simulate(const GearParams& params, const SimulationOptions& options);

// Seed 001's error-source form to TE terms (model.md §3), each named after its source.
std::vector<TeTerm> te_terms_from_error_sources(const ErrorSourceSet& set,
                                                const GearGeometry& geometry);

// Frequency [Hz] of a TE term at a constant input speed omega1 [rad/s].
double te_term_frequency_hz(const TeTerm& term, const GearGeometry& geometry, double omega1);

}  // namespace wavebench::model
