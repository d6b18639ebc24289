#pragma once
// The procedures speak of the gear's sense and TE in the model's terms (model.md §1); the bench
// below them uses the same definition without depending on the procedures.
#include "wavebench/model/gear_sense.hpp"

namespace wavebench::metrology {

using model::GearSense;
using model::kArcminPerRad;
using model::kArcsecPerRad;

}  // namespace wavebench::metrology
