#pragma once
// Kinematic transmission error e(theta1, theta2) and its rate (model.md §3). Written against the
// shaft angles, not time, so it stays right in ramps and at standstill.
#include <vector>

#include "wavebench/model/angle_phasor.hpp"
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct TeValue {
  double value = 0;  // e [rad at the output]
  double rate = 0;   // e' [rad/s]
};

class TeExcitation {
 public:
  TeExcitation() = default;
  explicit TeExcitation(const std::vector<TeTerm>& terms);

  TeValue evaluate(double theta1, double theta2, double omega1, double omega2) const noexcept;
  bool empty() const noexcept { return integer_terms_.empty() && other_terms_.empty(); }

 private:
  // Terms of equal integer orders are merged into one phasor A e^(i phi) (the sum of sines of
  // one argument is one sine), so each distinct line costs one evaluation.
  struct IntegerTerm {
    long order_input, order_output;
    Phasor amplitude;  // sum of A_j e^(i phi_j) (not of unit length)
  };
  struct Term {
    double amplitude, order_input, order_output, phase;
  };
  std::vector<IntegerTerm> integer_terms_;
  std::vector<Term> other_terms_;
  bool uses_input_angle_ = false;  // some term is built from powers of e^(i theta1)
  bool uses_output_angle_ = false;
};

}  // namespace wavebench::model
