#pragma once
// Linearly implicit 4th-order Rosenbrock method with an embedded 3rd-order error estimate and
// 3rd-order dense output: the six-stage, L-stable, stiffly accurate scheme of Hairer & Wanner
// (Solving ODEs II, §VI.4; the coefficient set Numerical Recipes and Boost.Odeint's rosenbrock4
// use), with Gustafsson's predictive step-size control. For stiff LuGre friction: the linear
// solves with (I/(γh) − J) keep it stable at steps far above 1/σ0.
// Two limits of long steps, both cured by StepControl::max_step: the dense output is 3rd
// order, so samples between steps err like h^4; and L-stability damps a mode that should
// grow (stick -> slip break-away), so at loose tolerances the block can stay stuck too long.

#include <Eigen/Dense>
#include <vector>

#include "wavebench/model/solver/integrator_base.hpp"

namespace wavebench::model::solver {

class Rosenbrock4 final : public AdaptiveIntegrator {
 public:
  explicit Rosenbrock4(const StepControl& control);

  std::string name() const override { return "Rosenbrock4"; }
  int order() const override { return 4; }

  std::span<const double> current_state() const override {
    return {y_.data(), static_cast<std::size_t>(y_.size())};
  }

 private:
  void DoInitialize(double h0) override;
  void DoReset(std::span<const double> y) override;
  double DoStep(double t_max) override;
  void DoLandInPlace() override;
  void DoDenseOutput(double t, std::span<double> y) const override;
  // df/dy and df/dt at (t_, y_) into jac_ and dfdt_ (analytic if the system has one).
  void evaluate_jacobian();
  // One trial step of size h from (t_, y_) into y_new_, error estimate into err_.
  void attempt(double h);

  double h_accepted_old_ = 0;
  bool first_step_ = true, jacobian_current_ = false;
  Eigen::VectorXd y_, y_old_, y_new_, y_stage_, f0_, f_stage_, dfdt_, err_, error_scale_;
  Eigen::VectorXd g1_, g2_, g3_, g4_, g5_, cont3_, cont4_;
  Eigen::MatrixXd jac_, iteration_matrix_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
};

}  // namespace wavebench::model::solver
