#pragma once
// The simulated torque sensor (node 4 by default): the shaft torque between the gear's output
// and the brake as one process value object whose index, sub-index, data type and scale come
// from the config, mapped into TPDO1 and sent on every SYNC.

#include <cstdint>
#include <random>

#include "wavebench/simdevices/canopen_node.hpp"

namespace wavebench::simdevices {

struct TorqueSensorConfig {
  std::uint8_t node_id = 4;
  // CiA 404 measuring device, analogue input.
  NodeIdentity identity{0x00020194, "WB-SIM torque sensor",
                        "1.0",      "wavebench-sim 0.1",
                        0x00000A57, 0x00000404,
                        0x00010000, 0x00004001};
  std::uint16_t index = 0x6130;  // process value object
  std::uint8_t sub = 1;
  DataType type = DataType::kInteger32;  // INTEGER16/32 (scaled) or REAL32 (scale applies too)
  double scale_nm_per_unit = 0.001;      // N*m per unit of the process value
  double noise_nm = 0.02;                // 1-sigma
  double offset_nm = 0;                  // zero error of the sensor
  std::uint64_t seed = 4;
  std::vector<FixedTpdo> fixed_tpdos;  // TPDOs a master cannot remap (issue 20)
};

class TorqueSensor final : public CanopenNode {
 public:
  TorqueSensor(const TorqueSensorConfig& config, FrameSink sink);

  // Reads the shaft torque [N*m] in the bench's output direction.
  void observe(double torque_nm);
  // The process value converted back to N*m.
  double value_nm() const;

 private:
  TorqueSensorConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace wavebench::simdevices
