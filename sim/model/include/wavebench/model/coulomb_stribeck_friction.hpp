#pragma once
// Coulomb + Stribeck + viscous friction at the wave generator (model.md §6), sign(omega)
// regularised by tanh(omega / smoothing_speed) so the right-hand side stays continuous.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

class CoulombStribeck {
 public:
  explicit CoulombStribeck(const CoulombStribeckFriction& p);
  double torque(double omega) const noexcept;

 private:
  CoulombStribeckFriction p_;
};

}  // namespace wavebench::model
