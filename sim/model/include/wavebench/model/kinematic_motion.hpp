#pragma once
// Prescribed input motion theta1(t): constant speed, a linear speed ramp from standstill, or a
// measured angle trace (monotone PCHIP through the samples, its slope for the speed).
#include <memory>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

struct InputMotion {
  double theta = 0, omega = 0, alpha = 0;
};

class KinematicMotion {
 public:
  explicit KinematicMotion(const KinematicInput& p);
  ~KinematicMotion();
  KinematicMotion(const KinematicMotion&);
  KinematicMotion& operator=(const KinematicMotion&);
  InputMotion at(double t) const noexcept;

 private:
  struct Trace;
  double speed_ = 0, ramp_ = 0;
  std::shared_ptr<const Trace> trace_;
};

}  // namespace wavebench::model
