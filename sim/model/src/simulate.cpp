// simulate(): the gear model on a TrajectoryRunner, sampled at a fixed rate (simulation.hpp).
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wavebench/model/gear_model.hpp"
#include "wavebench/model/simulation.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace wavebench::model {
namespace {

solver::IntegratorKind integrator_kind(SolverMethod m) {
  switch (m) {
    case SolverMethod::kRk4:
      return solver::IntegratorKind::kRk4;
    case SolverMethod::kRosenbrock4:
      return solver::IntegratorKind::kRosenbrock;
    default:
      return solver::IntegratorKind::kDormandPrince45;
  }
}

void reserve(SampledResponse& r, std::size_t n) {
  for (auto* v : {&r.t, &r.theta1, &r.omega1, &r.theta2_dev, &r.omega2, &r.alpha2, &r.twist,
                  &r.twist_rate, &r.te, &r.gear_torque, &r.load_torque, &r.motor_torque}) {
    v->reserve(n);
  }
}

}  // namespace

SimulationResult simulate(const GearParams& params, const SimulationOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.t_end > 0)) {
    throw std::invalid_argument("t_end = " + std::to_string(options.t_end) + " s: expected > 0");
  }
  if (!(options.transient >= 0) || options.transient > options.t_end) {
    throw std::invalid_argument("transient = " + std::to_string(options.transient) +
                                " s: expected 0 <= transient <= t_end (" +
                                std::to_string(options.t_end) + " s)");
  }
  if (!(options.sample_rate > 0)) {
    throw std::invalid_argument("sample_rate = " + std::to_string(options.sample_rate) +
                                " Hz: expected > 0");
  }

  const GearModel model(params, options.locate_events);
  auto integrator =
      solver::make_integrator(integrator_kind(options.method), {options.rtol, options.atol},
                              options.fixed_step, options.max_step);

  solver::TrajectoryOptions topt;
  topt.t_end = options.t_end;
  topt.sample_rate = options.sample_rate;
  topt.sample_t0 = options.transient;
  topt.locate_events = true;  // the model only declares the witnesses the options asked for
  solver::TrajectoryRunner runner(*integrator, model, topt);

  SimulationResult result;
  SampledResponse& s = result.response;
  reserve(s,
          static_cast<std::size_t>((options.t_end - options.transient) * options.sample_rate) + 2);
  const double t_first = options.transient - 0.5 / options.sample_rate;
  runner.on_sample([&](double t, std::span<const double> y, std::span<const double> d) {
    if (t < t_first) return;
    const GearOutputs o = model.outputs(t, y, d);
    s.t.push_back(t);
    s.theta1.push_back(o.theta1);
    s.omega1.push_back(o.omega1);
    s.theta2_dev.push_back(o.theta2_dev);
    s.omega2.push_back(o.omega2);
    s.alpha2.push_back(o.alpha2);
    s.twist.push_back(o.twist);
    s.twist_rate.push_back(o.twist_rate);
    s.te.push_back(o.te);
    s.gear_torque.push_back(o.gear_torque);
    s.load_torque.push_back(o.load_torque);
    s.motor_torque.push_back(o.motor_torque);
  });
  if (options.progress) runner.on_progress(options.progress);

  std::vector<double> y = model.initial_state();
  std::vector<double> d = model.initial_discrete();
  const solver::TrajectoryResult run = runner.run(0.0, y, d);

  result.stats.steps = run.counters.steps;
  result.stats.rejected_steps = run.counters.rejected_steps;
  result.stats.rhs_evaluations = run.counters.rhs_evaluations;
  result.stats.jacobian_evaluations = run.counters.jacobian_evaluations;
  result.stats.events = static_cast<std::int64_t>(run.events.size());
  result.events.reserve(run.events.size());
  for (const auto& e : run.events) {
    result.events.push_back({e.t, model.event_kind(e.witness, e.direction)});
  }
  result.dissipated_energy_j = y[static_cast<std::size_t>(model.layout().dissipated_energy)];
  result.stats.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace wavebench::model
