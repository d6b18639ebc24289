#include "wavebench/model/solver/integrators.hpp"

#include <stdexcept>

#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/rk4.hpp"
#include "wavebench/model/solver/rosenbrock4.hpp"

namespace wavebench::model::solver {

std::span<const IntegratorEntry> integrator_registry() {
  static const IntegratorEntry registry[] = {
      {IntegratorKind::kDormandPrince45, "DormandPrince45", true,
       [](const StepControl& c) -> std::unique_ptr<Integrator> {
         return std::make_unique<DormandPrince45>(StepControl{c.tolerances, c.max_step, 0.0});
       }},
      {IntegratorKind::kRk4, "Rk4", false,
       [](const StepControl& c) -> std::unique_ptr<Integrator> {
         return std::make_unique<Rk4>(c.fixed_step);
       }},
      {IntegratorKind::kRosenbrock, "Rosenbrock4", true,
       [](const StepControl& c) -> std::unique_ptr<Integrator> {
         return std::make_unique<Rosenbrock4>(StepControl{c.tolerances, c.max_step, 0.0});
       }},
  };
  return registry;
}

std::unique_ptr<Integrator> make_integrator(IntegratorKind kind, const Tolerances& tolerances,
                                            double fixed_step, double max_step) {
  for (const auto& entry : integrator_registry()) {
    if (entry.kind == kind) return entry.make(StepControl{tolerances, max_step, fixed_step});
  }
  throw std::invalid_argument("make_integrator: unknown IntegratorKind");
}

}  // namespace wavebench::model::solver
