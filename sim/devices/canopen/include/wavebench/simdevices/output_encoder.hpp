#pragma once
// The simulated output encoder (CiA 406, node 3 by default): a multi-turn absolute encoder on
// the gear's output flange. 0x6004 position value, 0x6501 single-turn resolution, 0x6502
// number of revolutions, 0x6000 code sequence, 0x6003 preset, Gaussian angle noise; TPDO1 maps
// 0x60040020 on every SYNC.

#include <cstdint>
#include <random>

#include "wavebench/simdevices/bench_plant.hpp"
#include "wavebench/simdevices/canopen_node.hpp"

namespace wavebench::simdevices {

struct EncoderConfig {
  std::uint8_t node_id = 3;
  NodeIdentity identity{0,          "WB-SIM output encoder",
                        "1.0",      "wavebench-sim 0.1",
                        0x00000A57, 0x00000406,
                        0x00010000, 0x00003001};    // device type derived
  std::uint32_t single_turn_resolution = 1U << 20;  // 0x6501 (and 0x6001)
  std::uint16_t revolutions = 2048;                 // 0x6502; 1 = single-turn (0x10196)
  double noise_rad = 2.4e-6;                        // 1-sigma angle noise (0.5 arcsec)
  std::uint64_t seed = 3;
  std::vector<FixedTpdo> fixed_tpdos;  // TPDOs a master cannot remap (issue 20)
};

class Cia406Encoder final : public CanopenNode {
 public:
  Cia406Encoder(const EncoderConfig& config, FrameSink sink);

  // Reads the shaft: `angle_rad` is the flange angle in the bench's output direction.
  void observe(double angle_rad);
  std::uint32_t position_value() const { return od().get<std::uint32_t>(0x6004, 0); }

 protected:
  void on_reset_application() override;

 private:
  std::int64_t raw_counts(double angle_rad) const;

  EncoderConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> noise_{0.0, 1.0};
  double angle_ = 0;
  std::int64_t preset_offset_ = 0;
};

}  // namespace wavebench::simdevices
