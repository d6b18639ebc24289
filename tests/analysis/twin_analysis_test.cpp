// The analysis of real twin runs (simulate()) on an XB-80-like gear with a linear stiffness and
// no backlash, where the linearised model is the exact reference: line amplitudes, attribution,
// orders, motion class, sweep and sensitivity against the closed-form transfer function.
#include "wavebench/analysis/twin_analysis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/analysis/signal_channel.hpp"

namespace wa = wavebench::analysis;
namespace wm = wavebench::model;

namespace {

constexpr double kArcsec = std::numbers::pi / 648000.0;
constexpr double kSpeed = 2680 * 2 * std::numbers::pi / 60;  // f_H = 44.667 Hz

wm::TeTerm term(const std::string& source, double arcsec, double a, double b, double phase) {
  wm::TeTerm t;
  t.source = source;
  t.amplitude_rad = arcsec * kArcsec;
  t.order_input = a;
  t.order_output = b;
  t.phase_rad = phase;
  return t;
}

wm::GearParams xb80_linear(bool single_term) {
  wm::GearParams p;
  p.name = "xb80-linear";
  p.geometry.z_flex = 268;
  p.geometry.z_circ = 270;
  p.geometry.wave_number = 2;
  p.geometry.ratio = 134;
  p.inertia_input = 2.2e-4;
  p.inertia_output = 0.2839;
  p.stiffness.law = wm::LinearPeriodicStiffness{1e6, {}};  // f_n = 298.7 Hz on the output
  p.damping.damping_ratio = 0.06;
  p.input = wm::KinematicInput{kSpeed, 0, {}, {}};
  p.nominal_input_speed = kSpeed;
  p.te_terms = {term("dF_i1 (Flexspline tangential composite error)", 20, 2, 2, 0.3)};
  if (!single_term) {
    p.te_terms.push_back(term("dS_fix (housing bore misalignment)", 6, 2, 0, 1.1));
    p.te_terms.push_back(term("T1l_1 (wave-generator/input assembly error)", 3, 1, 0, 0.0));
  }
  return p;
}

wm::SimulationOptions run_options(double t_end) {
  wm::SimulationOptions o;
  o.t_end = t_end;
  o.transient = 0.2;
  o.sample_rate = 2000;
  o.rtol = 1e-8;
  o.atol = 1e-12;
  return o;
}

double linear_amplitude(const wa::LinearGearCoefficients& co, const wm::GearParams& p,
                        std::size_t j, const std::string& signal) {
  const double f = wm::te_term_frequency_hz(p.te_terms[j], p.geometry, kSpeed);
  return std::abs(wa::te_transfer(co, signal, f)) * p.te_terms[j].amplitude_rad;
}

}  // namespace

TEST(TwinAnalysis, LinesAttributionOrdersAndModesOfAThreeTermRun) {
  const auto params = xb80_linear(false);
  const auto sim = run_options(4.2);
  const auto result = wm::simulate(params, sim);
  wa::AnalysisOptions options;
  options.spectrum.signal = "te";
  const auto a = wa::analyse_twin_run(params, sim, result, options);

  EXPECT_NEAR(a.mean_input_speed, kSpeed, 1e-6 * kSpeed);
  EXPECT_NEAR(a.spectrum.resolution_hz, 0.25, 1e-3);
  ASSERT_TRUE(a.linear.has_value());
  ASSERT_EQ(a.linear->modes.size(), 1u);
  EXPECT_NEAR(a.linear->modes[0].natural_frequency_hz,
              std::sqrt(1e6 / 0.2839) / (2 * std::numbers::pi), 1e-6);

  ASSERT_GE(a.peaks.size(), 3u);
  const double f_h = kSpeed / (2 * std::numbers::pi);
  const auto& top = a.peaks[0];
  EXPECT_NEAR(top.frequency_hz, 2 * (1 + 1.0 / 134) * f_h, 0.02);
  ASSERT_EQ(top.sources.size(), 1u);
  EXPECT_EQ(top.sources[0].source.substr(0, 5), "dF_i1");
  EXPECT_DOUBLE_EQ(top.sources[0].share, 1.0);
  const auto& co = a.linear->coefficients;
  EXPECT_NEAR(top.amplitude, linear_amplitude(co, params, 0, "te"),
              0.01 * linear_amplitude(co, params, 0, "te"));
  EXPECT_NEAR(top.predicted_amplitude, linear_amplitude(co, params, 0, "te"), 0.01 * top.amplitude);
  const auto& second = a.peaks[1];
  EXPECT_NEAR(second.frequency_hz, 2 * f_h, 0.02);
  ASSERT_EQ(second.sources.size(), 1u);
  EXPECT_EQ(second.sources[0].source.substr(0, 6), "dS_fix");
  EXPECT_NEAR(second.amplitude, linear_amplitude(co, params, 1, "te"),
              0.01 * linear_amplitude(co, params, 1, "te"));

  ASSERT_TRUE(a.orders.has_value());
  ASSERT_FALSE(a.orders->peaks.empty());
  EXPECT_NEAR(a.orders->peaks[0].order_input, 2 * (1 + 1.0 / 134), 2e-3);
  EXPECT_NEAR(a.orders->peaks[0].order_output, 270, 0.3);

  // The section strobed at the 90 Hz term does not repeat: the 89.3 Hz and 44.7 Hz lines beat.
  EXPECT_NE(a.motion.motion, wa::MotionClass::kPeriod1) << a.motion.summary;

  const auto j = wa::summary_json(a, result);
  for (const char* key : {"peaks", "motion", "natural_frequencies_hz", "sim_time_s", "steps",
                          "rhs_evaluations", "wall_s"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["peaks"][0]["sources"][0]["share"].get<double>(), 1.0);
  EXPECT_NEAR(j["sim_time_s"].get<double>(), 4.0, 1e-3);
  EXPECT_GT(j["steps"].get<long>(), 0);
  EXPECT_FALSE(j["motion"]["evidence"].get<std::string>().empty());
}

TEST(TwinAnalysis, SingleTermRunIsPeriodOneAndAlpha2MatchesTheTransferFunction) {
  const auto params = xb80_linear(true);
  const auto sim = run_options(1.2);
  const auto result = wm::simulate(params, sim);
  wa::AnalysisOptions options;
  options.spectrum.signal = "alpha2";
  const auto a = wa::analyse_twin_run(params, sim, result, options);
  EXPECT_EQ(a.motion.motion, wa::MotionClass::kPeriod1) << a.motion.summary;
  EXPECT_GT(a.motion.evidence.points, 50);
  ASSERT_FALSE(a.peaks.empty());
  const double expected = linear_amplitude(a.linear->coefficients, params, 0, "alpha2");
  EXPECT_NEAR(a.peaks[0].amplitude, expected, 0.01 * expected);
  EXPECT_NEAR(a.rms, expected / std::sqrt(2.0), 0.01 * expected);
  EXPECT_THROW(
      {
        auto bad = options;
        bad.spectrum.signal = "torque";
        wa::analyse_twin_run(params, sim, result, bad);
      },
      std::invalid_argument);
}

TEST(TwinAnalysis, SpeedSweepOfALinearGearFollowsTheResonanceWithoutHysteresis) {
  const auto params = xb80_linear(true);
  auto sim = run_options(1.0);
  wa::SweepOptions o;
  o.enabled = true;
  o.from_speed = 600;
  o.to_speed = 1200;
  o.steps = 7;
  o.settle_time = 0.25;
  o.record_time = 0.4;
  const auto sweep = wa::run_speed_sweep(params, sim, o, "te", &params.te_terms[0]);
  ASSERT_EQ(sweep.up.size(), 7u);
  ASSERT_EQ(sweep.down.size(), 7u);
  const auto gear = wa::linearise_gear(params, 0.0);
  for (const auto& p : sweep.up) {
    const double f = wm::te_term_frequency_hz(params.te_terms[0], params.geometry, p.speed);
    const double expected =
        std::abs(wa::te_transfer(gear.coefficients, "te", f)) * params.te_terms[0].amplitude_rad;
    EXPECT_NEAR(p.rms, expected / std::sqrt(2.0), 0.03 * expected) << p.speed;
    EXPECT_FALSE(p.poincare_x.empty());
  }
  EXPECT_LT(sweep.max_hysteresis, 0.05);
  EXPECT_TRUE(sweep.hysteresis_speeds.empty());
  EXPECT_DOUBLE_EQ(sweep.down.front().speed, 1200);
}

TEST(TwinAnalysis, FiniteDifferenceSensitivityAgreesWithTheLinearOne) {
  const auto params = xb80_linear(false);
  // 3 s recorded: two whole beats of the 89.3 and 90.0 Hz lines, so the RMS is their power sum.
  const auto sim = run_options(3.2);
  const auto result = wm::simulate(params, sim);
  const double rms = wa::rms_about_mean(result.response.te);
  const auto gear = wa::linearise_gear(params, 0.0);
  wa::SensitivityOptions o;
  o.enabled = true;
  o.relative_step = 0.1;
  o.monte_carlo_runs = 500;
  const auto s = wa::te_sensitivity(params, sim, o, "te", kSpeed, gear.coefficients, rms, true);
  ASSERT_EQ(s.sources.size(), 3u);
  EXPECT_EQ(s.sources[0].source.substr(0, 5), "dF_i1");
  for (const auto& src : s.sources) {
    EXPECT_NEAR(src.finite_difference, src.linear, 0.05 * std::abs(s.sources[0].linear))
        << src.source;
  }
  EXPECT_NEAR(s.rms_linear, rms, 0.03 * rms);
  EXPECT_LT(s.monte_carlo.mean, s.monte_carlo.nominal);
  EXPECT_GT(s.monte_carlo.p95, s.monte_carlo.mean);
}

TEST(TwinAnalysis, StiffnessVariationUnderLoadIsAttributedAsAnEquivalentError) {
  auto params = xb80_linear(true);
  // 3 % stiffness variation twice per WG revolution and 25 N m drag: the torque ripple
  // k_p * (T / k0) = 0.75 N m acts like a TE of 0.75 / k0 rad at 2 f_H = 89.33 Hz.
  params.stiffness.law = wm::LinearPeriodicStiffness{1e6, {{3e4, 2, 0, 0.0}}};
  params.load.output_drag_coulomb = 25;
  params.load.drag_smoothing_speed = 1e-3;
  // A small 90 Hz line: 2.7 bins away, the Hann skirt of a 20 arcsec line would bury this one.
  params.te_terms[0].amplitude_rad = 0.5 * kArcsec;
  const auto sim = run_options(4.2);
  const auto result = wm::simulate(params, sim);
  wa::AnalysisOptions options;
  options.spectrum.signal = "te";
  const auto a = wa::analyse_twin_run(params, sim, result, options);
  const double f_h = kSpeed / (2 * std::numbers::pi);
  const wa::AttributedPeak* ripple = nullptr;
  for (const auto& p : a.peaks) {
    if (std::abs(p.frequency_hz - 2 * f_h) < 0.05) ripple = &p;
  }
  std::string listing;
  for (const auto& p : a.peaks) {
    listing += std::to_string(p.frequency_hz) + " Hz " + std::to_string(p.amplitude) + " " +
               p.label + "; ";
  }
  ASSERT_NE(ripple, nullptr) << listing << " mean torque " << a.linear->operating_torque_nm;
  ASSERT_EQ(ripple->sources.size(), 1u);
  EXPECT_EQ(ripple->sources[0].source, "stiffness variation (2,0)");
  const double expected =
      std::abs(wa::te_transfer(a.linear->coefficients, "te", 2 * f_h)) * 0.75 / 1e6;
  EXPECT_NEAR(ripple->amplitude, expected, 0.05 * expected);
  EXPECT_NEAR(ripple->predicted_amplitude, expected, 1e-3 * expected);
}
