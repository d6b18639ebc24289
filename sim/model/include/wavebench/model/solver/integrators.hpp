#pragma once
// One place that turns a method choice from a config into an integrator.

#include <memory>

#include "wavebench/model/solver/integrator.hpp"

namespace wavebench::model::solver {

enum class IntegratorKind { kDormandPrince45, kRk4, kRosenbrock };

// fixed_step is the step of Rk4 (ignored by the adaptive methods); max_step = 0 means no limit.
// Throws std::invalid_argument naming the parameter when a value is out of range.
std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const Tolerances& tolerances,
                                            double fixed_step, double max_step);

}  // namespace wavebench::model::solver
