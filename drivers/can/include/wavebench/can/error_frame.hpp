#pragma once
// Turns a Linux CAN error frame (CAN_ERR_FLAG, classes from linux/can/error.h) into bus events.

#include <vector>

#include "wavebench/can/can_bus.hpp"

namespace wavebench::can {

// Every event the error frame reports, most severe first; empty for a non-error frame.
std::vector<BusEvent> classify_error_frame(const Frame& frame);

}  // namespace wavebench::can
