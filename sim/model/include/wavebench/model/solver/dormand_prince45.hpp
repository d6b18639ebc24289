#pragma once
// Dormand–Prince 5(4) (Hairer, Nørsett & Wanner's DOPRI5): FSAL, PI step-size control on the
// weighted RMS norm of the embedded error, and the method's own 4th-order continuous
// extension for dense output.

#include <vector>

#include "wavebench/model/solver/integrator_base.hpp"

namespace wavebench::model::solver {

class DormandPrince45 final : public AdaptiveIntegrator {
 public:
  explicit DormandPrince45(const StepControl& control);

  std::string name() const override { return "DormandPrince45"; }
  int order() const override { return 5; }

  std::span<const double> current_state() const override { return y_; }

 private:
  void DoInitialize(double h0) override;
  void DoReset(std::span<const double> y) override;
  double DoStep(double t_max) override;
  void DoLandInPlace() override;
  void DoDenseOutput(double t, std::span<double> y) const override;
  void prepare_dense_output() const;

  std::vector<double> y_, y_old_, y_stage_, y_new_, error_scale_;
  std::vector<double> k1_, k2_, k3_, k4_, k5_, k6_, k7_;
  // Continuous extension coefficients, built on the first dense_output() call of a step.
  mutable std::vector<double> r1_, r2_, r3_, r4_, r5_;
  mutable bool dense_ready_ = false;
};

}  // namespace wavebench::model::solver
