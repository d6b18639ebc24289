#pragma once
// Running a GearModel from a chosen initial state, for tests that need more than simulate()
// gives (a custom start, the energy state, every output).
#include <cmath>
#include <numbers>
#include <vector>

#include "wavebench/model/gear_model.hpp"
#include "wavebench/model/simulation.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace wavebench::model::testing {

inline constexpr double kArcsec = std::numbers::pi / 648000.0;

struct GearSample {
  double t = 0;
  GearOutputs out;
  std::vector<double> y;
};

struct GearRun {
  std::vector<GearSample> samples;
  solver::TrajectoryResult result;
  std::vector<double> y_end;
};

inline GearRun run_gear(const GearModel& model, std::vector<double> y, double t_end,
                        double sample_rate, double rtol = 1e-10, double atol = 1e-12,
                        solver::IntegratorKind kind = solver::IntegratorKind::kDormandPrince45,
                        double max_step = 0) {
  auto integrator = solver::make_integrator(kind, {rtol, atol}, 1e-5, max_step);
  solver::TrajectoryOptions opt;
  opt.t_end = t_end;
  opt.sample_rate = sample_rate;
  solver::TrajectoryRunner runner(*integrator, model, opt);
  GearRun run;
  runner.on_sample([&](double t, std::span<const double> ys, std::span<const double> d) {
    run.samples.push_back({t, model.outputs(t, ys, d), {ys.begin(), ys.end()}});
  });
  std::vector<double> d = model.initial_discrete();
  run.result = runner.run(0.0, y, d);
  run.y_end = y;
  return run;
}

// A gear with everything switched off but inertias and a constant stiffness.
inline GearParams bare_gear(double ratio, double j1, double j2, double k) {
  GearParams p;
  p.geometry.ratio = ratio;
  p.inertia_input = j1;
  p.inertia_output = j2;
  p.stiffness.law = LinearPeriodicStiffness{k, {}};
  p.input = TorqueInput{};
  return p;
}

}  // namespace wavebench::model::testing
