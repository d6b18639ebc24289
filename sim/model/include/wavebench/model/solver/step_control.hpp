#pragma once
// Settings shared by the integrators that pick their own step size.

#include <span>

#include "wavebench/model/solver/integrator.hpp"

namespace wavebench::model::solver {

struct StepControl {
  Tolerances tolerances;
  double max_step = 0;  // [s] 0 = no limit
  // > 0 switches step-size control off and takes steps of exactly this size (the last one
  // before t_max shorter). Meant for convergence-order measurements, not for production runs.
  double fixed_step = 0;
};

// Throws std::invalid_argument naming the field, the value and what was expected.
void validate(const StepControl& control);

// The system's error_scale() must be finite and > 0 for every state, else the error norm
// divides by zero; throws std::invalid_argument naming the index and the value.
void validate_error_scale(std::span<const double> scale);

}  // namespace wavebench::model::solver
