#pragma once
// Angle-periodic stiffness variation sum_p A_p cos(a_p theta1 + b_p theta2 + phi_p) (model.md §4).
#include <vector>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class PeriodicModulation {
 public:
  PeriodicModulation() = default;
  explicit PeriodicModulation(const std::vector<StiffnessHarmonic>& harmonics);

  double sum(double theta1, double theta2) const noexcept;
  bool empty() const noexcept { return harmonics_.empty(); }

 private:
  std::vector<StiffnessHarmonic> harmonics_;
};

}  // namespace wavebench::model
