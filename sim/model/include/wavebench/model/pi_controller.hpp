#pragma once
// The servo loops' control law, one for the model's drive (a solver owns the integral as a
// state) and the simulated CiA 402 drive (a fixed control period):
//   u = u_ff + Kp·(e + I/Ti),  I = ∫e dt,  |u| ≤ limit.
// Anti-windup by conditional integration: I does not grow while the output is at its limit and
// the error pushes it further. Ti = 0 makes it a P loop (no integral).
// Header-only: the simulated devices use the model's headers without linking the model.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::model {

struct PiOutput {
  double value = 0;          // u, limited
  double integral_rate = 0;  // dI/dt: e, or 0 while winding up or without integral action
  bool limited = false;      // the limit cut u
};

class PiController {
 public:
  static constexpr double kNoLimit = std::numeric_limits<double>::infinity();

  // gain Kp ≥ 0 (units of u per unit of e), integral_time Ti ≥ 0 [s] (0: P only).
  PiController(double gain, double integral_time) : gain_(gain), integral_time_(integral_time) {
    if (!(gain >= 0) || !(integral_time >= 0) || !std::isfinite(gain) ||
        !std::isfinite(integral_time)) {
      throw std::invalid_argument("PI gain " + std::to_string(gain) + ", integral time " +
                                  std::to_string(integral_time) + ": expected finite and >= 0");
    }
  }

  bool has_integral() const noexcept { return integral_time_ > 0; }

  // The law for error e and integral I (the caller's state); limit ≥ 0.
  PiOutput evaluate(double error, double integral, double limit = kNoLimit,
                    double feedforward = 0) const noexcept {
    const double demand =
        feedforward + gain_ * (error + (has_integral() ? integral / integral_time_ : 0.0));
    PiOutput out{demand, has_integral() ? error : 0.0, false};
    if (std::abs(demand) > limit) {
      out.value = std::copysign(limit, demand);
      out.limited = true;
      if (error * demand > 0) out.integral_rate = 0;
    }
    return out;
  }

  // One control period dt with the controller's own integral: the integral advances first
  // (rate from the output before the step) and its term is kept within ±limit.
  PiOutput step(double error, double dt, double limit = kNoLimit, double feedforward = 0) noexcept {
    integral_ += evaluate(error, integral_, limit, feedforward).integral_rate * dt;
    if (has_integral() && gain_ > 0 && std::isfinite(limit)) {
      const double bound = limit * integral_time_ / gain_;
      integral_ = std::clamp(integral_, -bound, bound);
    }
    return evaluate(error, integral_, limit, feedforward);
  }
  void reset() noexcept { integral_ = 0; }
  double integral() const noexcept { return integral_; }

 private:
  double gain_;
  double integral_time_;
  double integral_ = 0;  // I = ∫e dt of step()
};

}  // namespace wavebench::model
