#include "wavebench/metrology/dynamic_te_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "wavebench/analysis/spectral_peaks.hpp"
#include "wavebench/metrology/dynamic_te_input.hpp"

namespace wavebench::metrology {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kArcsec = kPi / 180 / 3600;

// XB-80-like gear: z_F = 160, z_C = 162, U = 2, N = 80; 100 rpm input; SYNC at 1 kHz with
// receive timestamps jittered by up to ±0.4 ms (the devices latch on SYNC; the angles are
// those at the sample's own time).
struct Record {
  std::vector<double> t, theta_in, theta_out, te_arcsec;
};

constexpr double kN = 80;
constexpr double kA1 = 20, kA2 = 12, kA3 = 5, kMean = 30;  // arcsec

double te_arcsec(double theta1, double theta2) {
  return kMean + kA1 * std::sin(theta2 + 0.3) + kA2 * std::sin(2 * theta1 + 2 * theta2 - 0.7) +
         kA3 * std::sin(160 * theta2 + 1.2);
}

Record make_record(int direction_sign) {
  Record r;
  const double omega = 100.0 / 60 * 2 * kPi;  // rad/s
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.4e-3, 0.4e-3);
  const int n = 105600;  // 2.2 output revolutions at 1 kHz
  for (int i = 0; i < n; ++i) {
    const double t = 1e-3 * i + jitter(rng) + 100.0;
    const double theta1 = omega * (t - 100.0) + 0.2;
    const double theta2_nominal = theta1 / kN;
    const double te = te_arcsec(theta1, theta2_nominal);
    const double theta2 = theta2_nominal + te * kArcsec;
    r.t.push_back(t);
    r.theta_in.push_back(theta1);
    r.theta_out.push_back(direction_sign * theta2);
    r.te_arcsec.push_back(te);
  }
  return r;
}

const NamedPeak* peak_named(const DynamicTeResult& r, const std::string& name) {
  for (const auto& p : r.peaks) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

TEST(DynamicTe, TraceStatisticsNamedOrderPeaksAndAliasing) {
  const auto rec = make_record(-1);
  const GearSense sense{kN, -1};
  const GearTeeth teeth{160, 162, 2};
  const std::vector<PredictedComponent> predicted = {
      {"dF_i1 (U,U)", 2, 2, kA2 * kArcsec},
      {"tooth mesh 2 z_C", 324, 0, 0.5 * kArcsec},  // 2·z_C·f_H = 540 Hz > 500 Hz
  };
  analysis::SpectrumAnalyser analyser;
  const auto r = analyse_dynamic_te(rec.t, rec.theta_in, rec.theta_out, sense, teeth, predicted,
                                    DynamicTeOptions{}, analyser);
  ASSERT_EQ(r.te_arcsec.size(), rec.t.size());
  for (std::size_t i = 0; i < rec.t.size(); i += 997) {
    ASSERT_NEAR(r.te_arcsec[i], rec.te_arcsec[i], 1e-6);  // arcsec (θ2 perturbation is O(1e-4))
  }
  double mean = 0, lo = 1e9, hi = -1e9;
  for (double v : rec.te_arcsec) {
    mean += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  mean /= static_cast<double>(rec.te_arcsec.size());
  EXPECT_NEAR(r.mean_arcsec, mean, 1e-6);
  EXPECT_NEAR(r.p2p_arcsec, hi - lo, 1e-6);
  // RMS about the mean of three sines, within the leakage of 2.2 revolutions of the 1/rev line.
  EXPECT_NEAR(r.rms_arcsec, std::sqrt((kA1 * kA1 + kA2 * kA2 + kA3 * kA3) / 2), 0.5);
  EXPECT_NEAR(r.output_revolutions, 2.2, 0.01);
  EXPECT_NEAR(r.input_speed_hz, 100.0 / 60, 1e-3);
  EXPECT_NEAR(r.sample_rate_hz, 1000, 0.1);

  const auto* once = peak_named(r, "output 1/rev");
  ASSERT_NE(once, nullptr);
  EXPECT_NEAR(once->order_output, 1.0, 0.02);
  EXPECT_NEAR(once->amplitude_arcsec, kA1, 0.02 * kA1);
  const auto* uu = peak_named(r, "dF_i1 (U,U)");
  ASSERT_NE(uu, nullptr);
  EXPECT_NEAR(uu->order_output, 162, 0.02);  // U·(N + 1) = z_C output orders
  EXPECT_NEAR(uu->order_input, 162 / kN, 1e-3);
  EXPECT_NEAR(uu->frequency_hz, 162 * (100.0 / 60) / kN, 0.01);
  EXPECT_NEAR(uu->amplitude_arcsec, kA2, 0.02 * kA2);
  const auto* mesh = peak_named(r, "mesh");
  ASSERT_NE(mesh, nullptr);
  EXPECT_NEAR(mesh->order_output, 160, 0.02);
  EXPECT_NEAR(mesh->amplitude_arcsec, kA3, 0.02 * kA3);

  // The (U,U) line in Hz, from the spectrum on the jittered timestamps.
  analysis::PeakSearch search;
  search.min_frequency_hz = 1.0;
  const auto hz_peaks = analysis::find_peaks(
      spectrum_on_timestamps(rec.t, rec.te_arcsec, analysis::Window::kHann, analyser), search);
  ASSERT_FALSE(hz_peaks.empty());
  EXPECT_NEAR(hz_peaks[0].frequency_hz, 162 * (100.0 / 60) / kN, 0.01);
  EXPECT_NEAR(hz_peaks[0].amplitude, kA2, 0.03 * kA2);

  // Welch over the two whole revolutions: bins at whole orders, where every line of this gear
  // falls (1, 160, 162), so each reads its amplitude.
  ASSERT_EQ(r.averaged_revolutions, 2u);
  ASSERT_GT(r.averaged_amplitude_arcsec.size(), 163u);
  EXPECT_DOUBLE_EQ(r.averaged_order_output[162], 162.0);
  EXPECT_NEAR(r.averaged_amplitude_arcsec[1], kA1, 0.01 * kA1);
  EXPECT_NEAR(r.averaged_amplitude_arcsec[160], kA3, 0.01 * kA3);
  EXPECT_NEAR(r.averaged_amplitude_arcsec[162], kA2, 0.01 * kA2);
  EXPECT_LT(r.averaged_amplitude_arcsec[100], 0.01);

  ASSERT_EQ(r.aliased.size(), 1u);
  EXPECT_EQ(r.aliased[0].name, "tooth mesh 2 z_C");
  EXPECT_NEAR(r.aliased[0].frequency_hz, 540, 0.5);
  EXPECT_NEAR(r.aliased[0].folded_hz, 460, 0.5);
  EXPECT_NEAR(r.aliased[0].amplitude_arcsec, 0.5, 1e-12);
  EXPECT_EQ(to_json(r)["aliased"].size(), 1u);
}

TEST(DynamicTe, FoldedFrequency) {
  EXPECT_DOUBLE_EQ(folded_frequency(540, 1000), 460);
  EXPECT_DOUBLE_EQ(folded_frequency(24120, 1000), 120);
  EXPECT_DOUBLE_EQ(folded_frequency(1990, 1000), 10);
}

TEST(DynamicTe, ShorterThanOneOutputRevolutionIsRejected) {
  auto rec = make_record(1);
  rec.t.resize(40000);
  rec.theta_in.resize(40000);
  rec.theta_out.resize(40000);
  analysis::SpectrumAnalyser analyser;
  EXPECT_THROW(analyse_dynamic_te(rec.t, rec.theta_in, rec.theta_out, GearSense{kN, 1},
                                  GearTeeth{160, 162, 2}, {}, DynamicTeOptions{}, analyser),
               std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::metrology

namespace wavebench::metrology {
namespace {

TEST(DynamicTeInput, KeepsValidSamplesOnTheirTimestampsAndCountsTheRest) {
  std::vector<storage::SyncSample> samples(6);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i].flags = storage::kAllChannelsValid;
    samples[i].receive_time_ns = 5'000'000'000 + static_cast<std::int64_t>(i) * 1'000'000;
    samples[i].theta_in_rad = static_cast<double>(i);
    samples[i].theta_out_rad = static_cast<double>(i) / 80;
  }
  samples[2].flags &= ~storage::kThetaOutValid;
  samples[4].receive_time_ns = samples[3].receive_time_ns;
  samples[5].missed_before = 3;
  samples[5].receive_time_ns += 3'000'000;
  const auto in = dynamic_te_input(samples);
  ASSERT_EQ(in.time_s.size(), 4u);
  EXPECT_EQ(in.skipped_invalid, 1u);
  EXPECT_EQ(in.skipped_out_of_order, 1u);
  EXPECT_EQ(in.missed_cycles, 3u);
  EXPECT_DOUBLE_EQ(in.time_s[3], 0.008);
  EXPECT_DOUBLE_EQ(in.theta_in_rad[2], 3.0);
  EXPECT_EQ(in.skipped_not_advancing, 0u);
}

// A repeated encoder value (a stale PDO on a loaded real-clock bench) or a step back is one
// sample skipped and counted, in either direction of turning: never the end of the analysis.
TEST(DynamicTeInput, OutputAnglesThatDoNotAdvanceAreSkippedAndCounted) {
  for (const double direction : {1.0, -1.0}) {
    std::vector<storage::SyncSample> samples(8);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      samples[i].flags = storage::kAllChannelsValid;
      samples[i].receive_time_ns = static_cast<std::int64_t>(i + 1) * 1'000'000;
      samples[i].theta_in_rad = static_cast<double>(i);
      samples[i].theta_out_rad = direction * static_cast<double>(i) / 80;
    }
    samples[3].theta_out_rad = samples[2].theta_out_rad;              // repeated
    samples[6].theta_out_rad = samples[5].theta_out_rad - direction;  // a step back
    const auto in = dynamic_te_input(samples);
    EXPECT_EQ(in.skipped_not_advancing, 2u) << direction;
    ASSERT_EQ(in.theta_out_rad.size(), 6u);
    for (std::size_t i = 1; i < in.theta_out_rad.size(); ++i) {
      EXPECT_GT((in.theta_out_rad[i] - in.theta_out_rad[i - 1]) * direction, 0) << i;
    }
  }
}

}  // namespace
}  // namespace wavebench::metrology
