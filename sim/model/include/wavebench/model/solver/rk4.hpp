#pragma once
// Classic fixed-step Runge–Kutta 4 with cubic Hermite dense output (the end-point slope is the
// next step's first stage, so the interpolant costs no extra evaluation).

#include <vector>

#include "wavebench/model/solver/integrator_base.hpp"

namespace wavebench::model::solver {

class Rk4 final : public IntegratorBase {
 public:
  // Throws std::invalid_argument unless step > 0 and finite.
  explicit Rk4(double step);

  std::string name() const override { return "Rk4"; }
  int order() const override { return 4; }

  std::span<const double> current_state() const override { return y_; }

 private:
  void DoInitialize(double h0) override;
  void DoReset(std::span<const double> y) override;
  double DoStep(double t_max) override;
  void DoLandInPlace() override;
  void DoDenseOutput(double t, std::span<double> y) const override;

  std::vector<double> y_, y_old_, f_, f_old_, k2_, k3_, k4_, y_stage_;
};

}  // namespace wavebench::model::solver
