// Peak attribution: terms matched by (folded) frequency, shares from the linear transfer
// function times the term amplitude, complex sums at one frequency, nonlinear combinations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "wavebench/analysis/peak_attribution.hpp"
#include "wavebench/model/simulation.hpp"

namespace wa = wavebench::analysis;
namespace wm = wavebench::model;

namespace {

wm::TeTerm term(const std::string& name, double amp, double a, double b, double phase = 0) {
  wm::TeTerm t;
  t.source = name + " (test source)";
  t.amplitude_rad = amp;
  t.order_input = a;
  t.order_output = b;
  t.phase_rad = phase;
  return t;
}

wa::AttributionInput xb80_input() {
  wa::AttributionInput in;
  in.geometry.z_flex = 268;
  in.geometry.z_circ = 270;
  in.geometry.wave_number = 2;
  in.geometry.ratio = 134;
  in.mean_input_speed = 2680 * 2 * std::numbers::pi / 60;  // f_H = 44.667 Hz
  in.sample_rate_hz = 10000;
  in.resolution_hz = 0.1;
  in.window = wa::Window::kHann;
  in.linear.inertia_output = 0.2839;
  in.linear.inertia_input = 2.2e-4;
  in.linear.ratio = 134;
  in.linear.stiffness = 1e5;
  in.linear.mesh_damping = 10;
  in.linear.input_prescribed = true;
  in.signal = "alpha2";
  in.terms = {term("dF_i1", 10e-6, 2, 2, 0.0),
              term("dF_i3", 5e-6, 2, 2, 0.0),
              term("T1k_1", 5e-6, 2, 2, std::numbers::pi),
              term("dS_fix", 4e-6, 2, 0),
              term("df_i1", 1e-7, 540, 0),
              term("T1l_1", 1e-6, 1, 0)};
  return in;
}

wa::SpectralPeak peak_at(double f, double a) {
  wa::SpectralPeak p;
  p.frequency_hz = f;
  p.amplitude = a;
  return p;
}

double share_sum(const wa::AttributedPeak& p, bool in_phase) {
  double s = 0;
  for (const auto& src : p.sources) s += in_phase ? src.in_phase_share : src.share;
  return s;
}

}  // namespace

TEST(PeakAttribution, FoldsFrequenciesAboveNyquist) {
  EXPECT_DOUBLE_EQ(wa::folded_frequency_hz(24120, 10000), 4120);
  EXPECT_DOUBLE_EQ(wa::folded_frequency_hz(7000, 10000), 3000);
  EXPECT_DOUBLE_EQ(wa::folded_frequency_hz(300, 10000), 300);
  EXPECT_DOUBLE_EQ(wa::bin_tolerance_hz(wa::Window::kHann, 0.5), 1.0);
}

TEST(PeakAttribution, RanksSourcesAtOneFrequencyByShare) {
  const auto in = xb80_input();
  const double f_h = 2680.0 / 60;
  const double f_tangential = 2 * (1 + 1.0 / 134) * f_h;
  const auto out = wa::attribute_peaks({peak_at(f_tangential, 1.0), peak_at(2 * f_h, 0.5)}, in);
  ASSERT_EQ(out.size(), 2u);
  const auto& p = out[0];
  EXPECT_EQ(p.label, "te");
  ASSERT_EQ(p.sources.size(), 3u);
  EXPECT_EQ(p.sources[0].source, "dF_i1 (test source)");
  // The same transfer function at one frequency: shares follow the amplitudes 10 : 5 : 5.
  EXPECT_NEAR(p.sources[0].share, 0.5, 1e-12);
  EXPECT_NEAR(p.sources[1].share, 0.25, 1e-12);
  EXPECT_NEAR(share_sum(p, false), 1.0, 1e-12);
  EXPECT_NEAR(share_sum(p, true), 1.0, 1e-12);
  // T1k_1 is in anti-phase: it cancels dF_i3, the resultant is dF_i1 alone.
  const double h = std::abs(wa::te_transfer(in.linear, "alpha2", f_tangential));
  EXPECT_NEAR(p.predicted_amplitude, 10e-6 * h, 1e-9 * h);
  EXPECT_NEAR(p.sources[0].in_phase_share, 1.0, 1e-12);
  for (const auto& s : p.sources) {
    if (s.source.rfind("T1k_1", 0) == 0) {
      EXPECT_NEAR(s.in_phase_share, -0.5, 1e-12);
    }
  }
  EXPECT_NEAR(p.sources[0].term_frequency_hz, f_tangential, 1e-9);
  // 89.33 Hz and 90.0 Hz are 0.67 Hz apart: with 0.1 Hz bins they are separate peaks.
  ASSERT_EQ(out[1].sources.size(), 1u);
  EXPECT_EQ(out[1].sources[0].source, "dS_fix (test source)");
  EXPECT_FALSE(out[1].aliased);
}

TEST(PeakAttribution, UnresolvedNeighboursShareOnePeakByTransferTimesAmplitude) {
  auto in = xb80_input();
  in.resolution_hz = 1.0;  // 89.33 and 90.0 Hz now fall into one peak's tolerance
  const double f_h = 2680.0 / 60;
  const auto out = wa::attribute_peaks({peak_at(2 * f_h, 1.0)}, in);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].sources.size(), 4u);
  const double h90 = std::abs(wa::te_transfer(in.linear, "alpha2", 2 * (1 + 1.0 / 134) * f_h));
  const double h89 = std::abs(wa::te_transfer(in.linear, "alpha2", 2 * f_h));
  const double total = 20e-6 * h90 + 4e-6 * h89;
  EXPECT_NEAR(out[0].sources[0].share, 10e-6 * h90 / total, 1e-12);
  EXPECT_NEAR(share_sum(out[0], false), 1.0, 1e-12);
  EXPECT_NEAR(share_sum(out[0], true), 1.0, 1e-12);
}

TEST(PeakAttribution, MarksAliasedToothMeshLine) {
  const auto in = xb80_input();
  const double f_mesh = 540 * 2680.0 / 60;  // 24120 Hz, sampled at 10 kHz -> 4120 Hz
  const auto out = wa::attribute_peaks({peak_at(4120, 1e-3)}, in);
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].sources.size(), 1u);
  EXPECT_TRUE(out[0].aliased);
  EXPECT_TRUE(out[0].sources[0].aliased);
  EXPECT_NEAR(out[0].sources[0].term_frequency_hz, f_mesh, 1e-6);
}

TEST(PeakAttribution, CombinationTonesAndStrangersAreLabelled) {
  const auto in = xb80_input();
  const double f_h = 2680.0 / 60;
  const double f_t = 2 * (1 + 1.0 / 134) * f_h;
  const auto out = wa::attribute_peaks(
      {peak_at(2 * f_t, 0.1), peak_at(f_t + f_h, 0.1), peak_at(1234.5, 0.1)}, in);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].label, "nonlinear: 2*dF_i1");
  EXPECT_TRUE(out[0].sources.empty());
  EXPECT_EQ(out[1].label, "nonlinear: dF_i1+T1l_1");
  EXPECT_EQ(out[2].label, "unattributed");
}
