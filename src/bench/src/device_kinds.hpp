#pragma once
// The kinds of channel devices, one per file; device_kind_registry.cpp lists them.

#include "wavebench/bench/channel_device.hpp"

namespace wavebench::bench {

ChannelDeviceKind cia406_encoder_kind();  // device_cia406_encoder.cpp
ChannelDeviceKind torque_sensor_kind();   // device_torque_sensor.cpp

}  // namespace wavebench::bench
