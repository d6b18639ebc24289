#include "wavebench/model/gear_sense.hpp"

#include <stdexcept>
#include <string>

namespace wavebench::model {

void GearSense::validate() const {
  if (!(ratio > 0)) {
    throw std::invalid_argument("gear ratio = " + std::to_string(ratio) + "; expected N > 0");
  }
  if (direction_sign != 1 && direction_sign != -1) {
    throw std::invalid_argument("gear direction_sign = " + std::to_string(direction_sign) +
                                "; expected +1 or -1");
  }
}

}  // namespace wavebench::model
