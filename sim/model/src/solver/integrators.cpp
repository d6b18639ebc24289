#include "wavebench/model/solver/integrators.hpp"

#include <stdexcept>

#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/rk4.hpp"
#include "wavebench/model/solver/rosenbrock4.hpp"

namespace wavebench::model::solver {

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const Tolerances& tolerances,
                                            double fixed_step, double max_step) {
  StepControl control{tolerances, max_step, 0.0};
  switch (kind) {
    case IntegratorKind::kDormandPrince45:
      return std::make_unique<DormandPrince45>(control);
    case IntegratorKind::kRk4:
      return std::make_unique<Rk4>(fixed_step);
    case IntegratorKind::kRosenbrock:
      return std::make_unique<Rosenbrock4>(control);
  }
  throw std::invalid_argument("make_integrator: unknown IntegratorKind");
}

}  // namespace wavebench::model::solver
