// Issue #12 acceptance on the in-process simulated bench: an endurance run of 10 output
// revolutions gives a per-revolution trend whose TE p2p (and mean, RMS) is the dynamic
// procedure's on the same revolutions. What is compared: the samples the bench produced during
// the run (kept here by a recorder beside the procedure), cut at each revolution's first and
// last receive time as the trend names them, through the dynamic procedure's own input and
// analysis (metrology::dynamic_te_input, analyse_dynamic_te). So the test checks that the
// streaming cut loses, doubles and reorders nothing, and that each revolution is one whole
// output turn.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "simulated_bench_fixture.hpp"
#include "wavebench/metrology/dynamic_te_input.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/endurance_procedure.hpp"
#include "wavebench/procedures/sample_recorder.hpp"

namespace wavebench::procedures {
namespace {

using testing::Sim;

std::vector<storage::SyncSample> between(const std::vector<storage::SyncSample>& all,
                                         std::int64_t first_ns, std::int64_t last_ns) {
  std::vector<storage::SyncSample> out;
  for (const auto& s : all) {
    if (s.receive_time_ns >= first_ns && s.receive_time_ns <= last_ns) out.push_back(s);
  }
  return out;
}

TEST(EnduranceAcceptance, TenRevolutionTrendMatchesTheDynamicAnalysisOfTheSameRevolutions) {
  Sim sim;
  const auto& d = sim.bench->description();
  EnduranceOptions o;
  o.input_rpm = 600;
  o.run_in_s = 0.5;
  o.output_revolutions = 10;
  o.load_nm = 20;
  const EnduranceProcedure procedure(o);
  SampleRecorder recorder;
  ObserverRegistration registration(*sim.bench, recorder);
  recorder.start();
  const auto out = procedure.run(*sim.bench);
  recorder.stop();

  ASSERT_EQ(out.revolutions.size(), 10u);
  const auto teeth = gear_teeth(d.twin_gear, d.sense.ratio);
  const auto predicted = predicted_components(d.twin_gear, teeth);
  ASSERT_EQ(out.mesh_orders.size(), 3u);
  EXPECT_EQ(out.mesh_orders[0], teeth.z_flex);
  for (std::size_t i = 0; i < out.revolutions.size(); ++i) {
    const auto& r = out.revolutions[i];
    SCOPED_TRACE("revolution " + std::to_string(r.revolution));
    EXPECT_EQ(r.revolution, static_cast<int>(i) + 1);
    EXPECT_TRUE(r.error.empty()) << r.error;
    if (i > 0) {
      // Contiguous: each revolution starts on the sample that closed the one before.
      EXPECT_EQ(r.first_receive_time_ns, out.revolutions[i - 1].last_receive_time_ns);
    }
    const auto samples =
        between(recorder.samples(), r.first_receive_time_ns, r.last_receive_time_ns);
    const auto input = metrology::dynamic_te_input(samples);
    ASSERT_EQ(input.time_s.size(), r.samples);
    metrology::DynamicTeOptions analysis;
    analysis.harmonics = o.mesh_harmonics;
    analysis.input_resolution_rad = d.input_encoder_resolution_rad;
    analysis.output_resolution_rad = d.output_encoder_resolution_rad;
    analysis::SpectrumAnalyser analyser;
    const auto dyn =
        metrology::analyse_dynamic_te(input.time_s, input.theta_in_rad, input.theta_out_rad,
                                       d.sense, teeth, predicted, analysis, analyser);
    EXPECT_NEAR(r.p2p_arcsec, dyn.p2p_arcsec, 1e-9);
    EXPECT_NEAR(r.mean_arcsec, dyn.mean_arcsec, 1e-9);
    EXPECT_NEAR(r.rms_arcsec, dyn.rms_arcsec, 1e-9);
    // One whole output turn, closed on the first sample past it.
    EXPECT_GE(dyn.output_revolutions, 1.0);
    EXPECT_LT(dyn.output_revolutions, 1.001);
    EXPECT_GT(r.p2p_arcsec, 0.0);
    ASSERT_EQ(r.mesh_arcsec.size(), 3u);
    EXPECT_GT(r.mesh_arcsec[0], 0.0);
    EXPECT_TRUE(r.brake_temperature_c.has_value());
    std::printf(
        "rev %2d  %7zu samples  mean %8.3f  p2p %8.3f  rms %7.3f  mesh %7.3f arcsec  "
        "brake %s\n",
        r.revolution, r.samples, r.mean_arcsec, r.p2p_arcsec, r.rms_arcsec, r.mesh_arcsec[0],
        r.brake_temperature_c ? std::to_string(*r.brake_temperature_c).c_str() : "-");
  }
  // Every recorded sample is in one revolution (and only the boundaries in two).
  const auto j = out.to_json();
  EXPECT_EQ(j["summary"]["revolutions_analysed"], 10);
  EXPECT_EQ(j["revolutions"].size(), 10u);
  EXPECT_DOUBLE_EQ(j["summary"]["p2p_first_arcsec"].get<double>(), out.revolutions[0].p2p_arcsec);
}

TEST(EnduranceAcceptance, OptionsOutOfRangeAreRefusedNamingTheKey) {
  try {
    EnduranceOptions::from_json({{"output_revolutions", 0}});
    FAIL() << "output_revolutions 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("endurance.output_revolutions"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(EnduranceOptions::from_json({{"hours", 2}}), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::procedures
