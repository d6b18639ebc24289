#pragma once
// One place that turns a method choice from a config into an integrator: the registry of every
// integrator. A new method is one row there; the contract tests (tests/model/solver) walk it.

#include <memory>
#include <span>
#include <string_view>

#include "wavebench/model/solver/integrator.hpp"
#include "wavebench/model/solver/step_control.hpp"

namespace wavebench::model::solver {

enum class IntegratorKind { kDormandPrince45, kRk4, kRosenbrock };

struct IntegratorEntry {
  IntegratorKind kind;
  std::string_view name;  // as Integrator::name() says
  bool adaptive;          // picks its own steps (StepControl); else steps of fixed_step
  // control.fixed_step is the fixed method's step; control.max_step = 0 means no limit.
  std::unique_ptr<Integrator> (*make)(const StepControl& control);
};

std::span<const IntegratorEntry> integrator_registry();

// fixed_step is the step of Rk4 (ignored by the adaptive methods); max_step = 0 means no limit.
// Throws std::invalid_argument naming the parameter when a value is out of range.
std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const Tolerances& tolerances,
                                            double fixed_step, double max_step);

}  // namespace wavebench::model::solver
