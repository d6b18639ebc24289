#include "wavebench/model/solver/step_control.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::model::solver {
namespace {

void require(bool ok, const char* key, double value, const char* expected) {
  if (!ok) {
    throw std::invalid_argument(std::string("solver option ") + key + " = " +
                                std::to_string(value) + ": expected " + expected);
  }
}

}  // namespace

void validate(const StepControl& control) {
  const Tolerances& tol = control.tolerances;
  require(std::isfinite(tol.rtol) && tol.rtol > 0, "rtol", tol.rtol, "a finite number > 0");
  require(std::isfinite(tol.atol) && tol.atol > 0, "atol", tol.atol, "a finite number > 0");
  require(std::isfinite(control.max_step) && control.max_step >= 0, "max_step", control.max_step,
          "a finite number >= 0 (0 = no limit)");
  require(std::isfinite(control.fixed_step) && control.fixed_step >= 0, "fixed_step",
          control.fixed_step, "a finite number >= 0 (0 = adaptive)");
}

void validate_error_scale(std::span<const double> scale) {
  for (std::size_t i = 0; i < scale.size(); ++i) {
    if (!(std::isfinite(scale[i]) && scale[i] > 0)) {
      throw std::invalid_argument("OdeSystem::error_scale()[" + std::to_string(i) +
                                  "] = " + std::to_string(scale[i]) +
                                  ": expected a finite characteristic size > 0");
    }
  }
}

}  // namespace wavebench::model::solver
