#pragma once
// Classic fixed-step Runge–Kutta 4 with cubic Hermite dense output (the end-point slope is the
// next step's first stage, so the interpolant costs no extra evaluation).

#include <vector>

#include "wavebench/model/solver/integrator.hpp"

namespace wavebench::model::solver {

class Rk4 final : public Integrator {
 public:
  // Throws std::invalid_argument unless step > 0 and finite.
  explicit Rk4(double step);

  std::string name() const override { return "Rk4"; }
  int order() const override { return 4; }

  void initialize(const OdeSystem& system, double t0, std::span<const double> y0,
                  std::span<const double> d, double h0) override;
  double step(double t_max) override;
  void dense_output(double t, std::span<double> y) const override;

  double current_time() const override { return t_; }
  double previous_time() const override { return t_old_; }
  std::span<const double> current_state() const override { return y_; }
  void reset(double t, std::span<const double> y) override;
  const IntegratorCounters& counters() const override { return counters_; }

 private:
  void evaluate(double t, const double* y, double* dydt);

  double h_;
  const OdeSystem* system_ = nullptr;
  std::span<const double> d_;
  std::size_t n_ = 0;
  double t_ = 0, t_old_ = 0;
  std::vector<double> y_, y_old_, f_, f_old_, k2_, k3_, k4_, y_stage_;
  IntegratorCounters counters_;
};

}  // namespace wavebench::model::solver
