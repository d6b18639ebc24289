#pragma once
// The per-sample limits of bench.md §7: input speed, brake current and torque, measured torque,
// following error, coil temperature, TE excursion. Returns the first limit crossed as a
// sentence naming the channel, the value and the limit; channels not valid in the sample are
// not judged. TE excursion is |TE − TE₀| with TE₀ the first complete sample's TE, because the
// two encoders' zeros are arbitrary. The input speed limit judges both the drive's 0x606C and
// the output encoder's speed × N (encoder_input_speed.hpp), which no drive unit can blind.

#include <optional>
#include <string>

#include "wavebench/bench/bench_description.hpp"
#include "wavebench/bench/cycle_record.hpp"
#include "wavebench/bench/encoder_input_speed.hpp"
#include "wavebench/model/gear_sense.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::bench {

class SafetyLimitsCheck {
 public:
  SafetyLimitsCheck(SafetyLimits limits, model::GearSense sense)
      : limits_(limits), sense_(sense), encoder_speed_(sense) {}

  // coil_temperature_c: the brake's latest fresh readback, if any.
  std::optional<std::string> check(const storage::SyncSample& sample, const DriveCycleValues& drive,
                                   std::optional<double> coil_temperature_c);
  // Forget TE₀ (after a fault is cleared, the next complete sample sets it again) and the
  // encoder speed's window.
  void reset_reference() noexcept {
    have_te0_ = false;
    encoder_speed_.reset();
  }
  SafetyLimits& limits() noexcept { return limits_; }

 private:
  SafetyLimits limits_;
  model::GearSense sense_;
  EncoderInputSpeed encoder_speed_;
  bool have_te0_ = false;
  double te0_ = 0;
};

}  // namespace wavebench::bench
