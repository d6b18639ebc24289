#pragma once
// A gear f times as stiff as its stiffness law (model.md §4): the simulated unit's variation
// of its case and the twin calibration's fitted correction use this one definition.
#include "wavebench/model/gear_params.hpp"

namespace wavebench::model {

// Every stiffness coefficient of the law times f, and K-bar with it. For forms 1, 2 and 4-7
// that is f times the torque at the same twist history: form 6's memory z' = A·x' − B·z scales
// with A, so A is scaled too. Form 3's breakpoints are torques (the catalogue's T1, T2): they
// stay, each segment is f times as stiff, so any torque gives 1/f the twist. The modulation is
// relative and stays. Throws std::invalid_argument unless f > 0.
void scale_stiffness(StiffnessParams& stiffness, double f);

}  // namespace wavebench::model
