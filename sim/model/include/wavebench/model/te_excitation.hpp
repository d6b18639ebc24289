#pragma once
// Kinematic transmission error e(theta1, theta2) and its rate (model.md §3). Written against the
// shaft angles, not time, so it stays right in ramps and at standstill.
#include <vector>

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
  bool empty() const noexcept { return terms_.empty(); }

 private:
  struct Term {
    double amplitude, order_input, order_output, phase;
  };
  std::vector<Term> terms_;
};

}  // namespace wavebench::model
