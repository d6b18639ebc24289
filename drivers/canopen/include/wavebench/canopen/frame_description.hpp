#pragma once
// Decodes any frame of the pre-defined connection set into one line of text, for
// `wavebench can dump` and logs: "SDO 601 node 1 request initiate upload 1018:01".

#include <string>

#include "wavebench/can/frame.hpp"

namespace wavebench::canopen {

std::string describe_frame(const can::Frame& frame);

}  // namespace wavebench::canopen
