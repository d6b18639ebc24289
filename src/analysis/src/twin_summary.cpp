#include <cmath>

#include "wavebench/analysis/twin_analysis.hpp"
#include "wavebench/analysis/window.hpp"

namespace wavebench::analysis {
namespace {

// JSON has no NaN: a quantity that was not computed is null.
nlohmann::json number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json sweep_points(const std::vector<SweepPoint>& points) {
  auto out = nlohmann::json::array();
  for (const auto& p : points) {
    out.push_back({{"speed_rad_s", p.speed},
                   {"rms", p.rms},
                   {"amplitude", p.amplitude},
                   {"poincare_x", p.poincare_x}});
  }
  return out;
}

}  // namespace

nlohmann::json summary_json(const TwinAnalysis& a, const model::SimulationResult& result) {
  nlohmann::json j;
  j["signal"] = a.signal;
  j["mean_input_speed_rad_s"] = a.mean_input_speed;
  j["rms"] = a.rms;
  j["spectrum"] = {{"resolution_hz", a.spectrum.resolution_hz},
                   {"sample_rate_hz", a.spectrum.sample_rate_hz},
                   {"samples", a.spectrum.samples},
                   {"window", window_name(a.spectrum.window)}};
  auto peaks = nlohmann::json::array();
  for (const auto& p : a.peaks) {
    auto sources = nlohmann::json::array();
    for (const auto& s : p.sources) {
      sources.push_back({{"source", s.source},
                         {"share", s.share},
                         {"in_phase_share", s.in_phase_share},
                         {"term_freq_hz", s.term_frequency_hz},
                         {"predicted_amplitude", s.predicted_amplitude},
                         {"aliased", s.aliased}});
    }
    peaks.push_back({{"freq_hz", p.frequency_hz},
                     {"amplitude", p.amplitude},
                     {"predicted_amplitude", p.predicted_amplitude},
                     {"tolerance_hz", p.tolerance_hz},
                     {"aliased", p.aliased},
                     {"label", p.label},
                     {"sources", sources}});
  }
  j["peaks"] = peaks;
  if (a.orders) {
    auto op = nlohmann::json::array();
    for (const auto& p : a.orders->peaks) {
      op.push_back({{"order_input", p.order_input},
                    {"order_output", p.order_output},
                    {"amplitude", p.amplitude}});
    }
    j["orders"] = {{"resolution", a.orders->order_resolution},
                   {"revolutions", a.orders->revolutions},
                   {"peaks", op}};
  }
  const auto& ev = a.motion.evidence;
  j["motion"] = {{"class", motion_class_name(a.motion.motion)},
                 {"clusters", ev.clusters},
                 {"period", ev.period},
                 {"spread", ev.spread},
                 {"cluster_tolerance", ev.cluster_tolerance},
                 {"correlation_dimension", ev.correlation_dimension},
                 {"lyapunov_per_period", ev.lyapunov_per_period},
                 {"points", ev.points},
                 {"excitation_source", a.poincare.excitation_source},
                 {"excitation_freq_hz", a.poincare.excitation_frequency_hz},
                 {"evidence", a.motion.summary}};
  auto natural = nlohmann::json::array();
  if (a.linear) {
    auto modes = nlohmann::json::array();
    auto zetas = nlohmann::json::array();
    for (const auto& m : a.linear->modes) {
      natural.push_back(m.natural_frequency_hz);
      zetas.push_back(m.damping_ratio);
      modes.push_back({{"freq_hz", m.natural_frequency_hz},
                       {"damping_ratio", m.damping_ratio},
                       {"shape_input_at_output", m.shape_input},
                       {"shape_output", m.shape_output}});
    }
    j["modes"] = modes;
    j["damping_ratios"] = zetas;
    j["mean_stiffness_nm_per_rad"] = a.linear->coefficients.stiffness;
    j["mesh_damping"] = a.linear->coefficients.mesh_damping;
    j["operating_twist_rad"] = a.linear->operating_twist_rad;
    j["stiffness_note"] = a.linear->stiffness_note;
  }
  j["natural_frequencies_hz"] = natural;
  if (a.sweep) {
    auto jumps = nlohmann::json::array();
    for (const auto& jp : a.sweep->jumps) {
      jumps.push_back({{"direction", jp.direction},
                       {"from_speed_rad_s", jp.from_speed},
                       {"to_speed_rad_s", jp.to_speed},
                       {"from_amplitude", jp.from_amplitude},
                       {"to_amplitude", jp.to_amplitude},
                       {"relative_change", jp.relative_change}});
    }
    j["sweep"] = {{"up", sweep_points(a.sweep->up)},
                  {"down", sweep_points(a.sweep->down)},
                  {"jumps", jumps},
                  {"max_hysteresis", a.sweep->max_hysteresis},
                  {"hysteresis_speed_rad_s", a.sweep->hysteresis_speed},
                  {"hysteresis_area", a.sweep->hysteresis_area},
                  {"hysteresis_speeds_rad_s", a.sweep->hysteresis_speeds}};
  }
  if (a.sensitivity) {
    const auto& s = *a.sensitivity;
    auto sources = nlohmann::json::array();
    for (const auto& src : s.sources) {
      sources.push_back({{"source", src.source},
                         {"amplitude_rad", src.amplitude_rad},
                         {"freq_hz", src.frequency_hz},
                         {"linear", src.linear},
                         {"finite_difference", number(src.finite_difference)}});
    }
    const auto& mc = s.monte_carlo;
    j["sensitivity"] = {{"signal", s.signal},
                        {"method", s.method},
                        {"rms_nominal", s.rms_nominal},
                        {"rms_linear", s.rms_linear},
                        {"sources", sources},
                        {"monte_carlo",
                         {{"runs", mc.runs},
                          {"seed", mc.seed},
                          {"method", "linear transfer function"},
                          {"mean", mc.mean},
                          {"stddev", mc.stddev},
                          {"p50", mc.p50},
                          {"p95", mc.p95},
                          {"max", mc.max},
                          {"nominal", mc.nominal}}}};
  }
  const auto& r = result.response;
  j["sim_time_s"] = r.t.size() >= 2 ? r.t.back() - r.t.front() : 0.0;
  j["steps"] = result.stats.steps;
  j["rejected_steps"] = result.stats.rejected_steps;
  j["rhs_evaluations"] = result.stats.rhs_evaluations;
  j["events"] = result.stats.events;
  j["wall_s"] = result.stats.wall_s;
  return j;
}

}  // namespace wavebench::analysis
