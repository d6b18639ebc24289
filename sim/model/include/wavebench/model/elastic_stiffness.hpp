#pragma once
// Memoryless stiffness forms 1-4 (model.md §4) acting on the backlash-filtered twist x.
#include <memory>
#include <variant>
#include <vector>

#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/periodic_modulation.hpp"

namespace wavebench::model {

// 3: K1 up to T1, K2 up to T2, K3 above; odd.
class ThreeSegmentCurve {
 public:
  explicit ThreeSegmentCurve(const ThreeSegmentStiffness& p);
  double torque(double x) const noexcept;
  double twist_at(double torque) const noexcept;  // inverse, for checks and preload

 private:
  ThreeSegmentStiffness p_;
  double x1_ = 0, x2_ = 0;  // twist at T1 and T2
};

// 4: monotone (PCHIP) curve through the measured points, odd-extended, linear beyond the last.
class TableCurve {
 public:
  explicit TableCurve(const TableStiffness& p);
  ~TableCurve();
  TableCurve(const TableCurve&);
  TableCurve& operator=(const TableCurve&);
  double torque(double x) const noexcept;
  double initial_slope() const noexcept { return slope0_; }

 private:
  struct Interpolant;
  std::shared_ptr<const Interpolant> interp_;
  double x_last_ = 0, t_last_ = 0, slope_last_ = 0, slope0_ = 0;
};

// T = curve(x) * (1 + relative(angles)) + x * absolute(angles); form 1's harmonics are the
// absolute part (k = k0 + sum k_p cos), the shared modulation of forms 2-4 the relative one.
class ElasticStiffness {
 public:
  // Throws std::invalid_argument if params.law is not one of forms 1-4.
  explicit ElasticStiffness(const StiffnessParams& params);

  double torque(double x, double theta1, double theta2) const noexcept;
  double torque_unmodulated(double x) const noexcept;
  double small_twist_stiffness() const noexcept;  // slope at x = 0, for K-bar when not given

 private:
  struct Linear {
    double k0;
  };
  std::variant<Linear, CubicStiffness, ThreeSegmentCurve, TableCurve> curve_;
  PeriodicModulation absolute_;
  PeriodicModulation relative_;
};

bool is_elastic(const StiffnessLaw& law) noexcept;

}  // namespace wavebench::model
