#include "wavebench/twin/twin_calibrator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "wavebench/config/twin_case_writer.hpp"
#include "wavebench/model/elastic_stiffness.hpp"
#include "wavebench/model/stiffness_scaling.hpp"
#include "wavebench/storage/atomic_file.hpp"
#include "wavebench/twin/twin_overlay.hpp"

namespace wavebench::twin {
namespace {

using metrology::HarmonicOrder;
using metrology::kArcminPerRad;
using metrology::kArcsecPerRad;

// The nominal terms' orders, then the standard families of model.md §3, each once.
std::vector<HarmonicOrder> candidate_orders(const model::GearParams& g,
                                            const std::vector<HarmonicOrder>& extra) {
  std::vector<HarmonicOrder> out;
  auto add = [&](const std::string& name, double a, double b) {
    if (a == 0 && b == 0) return;  // the constant is the fit's offset
    for (const auto& o : out) {
      if (o.order_input == a && o.order_output == b) return;
    }
    out.push_back({name, a, b});
  };
  for (const auto& t : g.te_terms) add(t.source, t.order_input, t.order_output);
  const double u = g.geometry.wave_number;
  add("wave generator (1, 0)", 1, 0);
  add("housing / fixed spline (U, 0)", u, 0);
  add("output-side tangential (U, U)", u, u);
  add("output once-per-rev (0, 1)", 0, 1);
  add("output 2/rev (0, 2)", 0, 2);
  if (g.geometry.z_circ > 0) add("tooth mesh (U*z_C, 0)", u * g.geometry.z_circ, 0);
  if (g.geometry.z_flex > 0) add("Flexspline teeth (0, z_F)", 0, g.geometry.z_flex);
  for (const auto& o : extra) add(o.name, o.order_input, o.order_output);
  return out;
}

// Adds δ·sin(u + δφ) to the first term of the same orders, or appends a new term.
void merge_harmonic(std::vector<model::TeTerm>& terms, const metrology::FittedHarmonic& h) {
  for (auto& t : terms) {
    if (t.order_input != h.order_input || t.order_output != h.order_output) continue;
    const double s =
        t.amplitude_rad * std::cos(t.phase_rad) + h.amplitude_rad * std::cos(h.phase_rad);
    const double c =
        t.amplitude_rad * std::sin(t.phase_rad) + h.amplitude_rad * std::sin(h.phase_rad);
    t.amplitude_rad = std::hypot(s, c);
    t.phase_rad = std::atan2(c, s);
    return;
  }
  model::TeTerm t;
  t.source = h.name + " (calibrated)";
  t.family = model::TeFamily::kCustom;
  t.amplitude_rad = h.amplitude_rad;
  t.order_input = h.order_input;
  t.order_output = h.order_output;
  t.phase_rad = h.phase_rad;
  terms.push_back(t);
}

// A constant TE: A·sin(0 + φ) with φ = ±π/2.
void merge_offset(std::vector<model::TeTerm>& terms, double offset_rad) {
  for (auto& t : terms) {
    if (t.order_input != 0 || t.order_output != 0) continue;
    const double total = t.amplitude_rad * std::sin(t.phase_rad) + offset_rad;
    t.amplitude_rad = std::abs(total);
    t.phase_rad = total < 0 ? -std::numbers::pi / 2 : std::numbers::pi / 2;
    return;
  }
  model::TeTerm t;
  t.source = "encoder zero offset (calibrated)";
  t.family = model::TeFamily::kCustom;
  t.amplitude_rad = std::abs(offset_rad);
  t.phase_rad = offset_rad < 0 ? -std::numbers::pi / 2 : std::numbers::pi / 2;
  terms.push_back(t);
}

// Twist of the nominal law under `torque` (elastic forms only; 0 when not elastic).
double nominal_twist(const model::StiffnessParams& s, double torque) {
  if (!model::is_elastic(s.law)) return 0;
  const model::ElasticStiffness law(s);
  double lo = 0, hi = 1e-6;
  for (int i = 0; i < 200 && law.torque_unmodulated(hi) < torque; ++i) hi *= 2;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (law.torque_unmodulated(mid) < torque ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Span between the q and 1 − q quantiles.
double percentile_span(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const auto at = [&](double f) {
    const auto k = static_cast<std::size_t>(f * static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  };
  const double lo = at(q);
  return at(1 - q) - lo;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / n;
    mb += b[i] / n;
  }
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

// A replay's figures: its points are let go as they settle (a run's worth of points is
// 100 bytes a sample), through `on_point` to whoever needs them.
struct Replay {
  TwinSolverOptions solver;
  model::GearParams params;
  metrology::TwinResidual residual;
  double noise_floor_arcsec = 0;
};

using PointSink = std::function<void(const TwinPoint&)>;

Replay replay(const model::GearParams& params, const metrology::GearSense& sense,
              std::span<const storage::SyncSample> samples, const TwinSolverOptions& solver,
              const PointSink& on_point = {}) {
  MeasuredDriveTwin twin(params, sense, solver);
  TwinOverlaySum sum;
  std::vector<TwinPoint> settled;
  const auto drain = [&] {
    settled.clear();
    twin.take_settled_points(settled);
    for (const auto& p : settled) {
      sum.add(p);
      if (on_point) on_point(p);
    }
  };
  for (std::size_t i = 0; i < samples.size(); ++i) {
    twin.push(twin_input(samples[i]));
    if (i % 4096 == 4095) drain();
  }
  twin.flush();
  drain();
  return {solver, params, sum.residual(), sum.noise_floor_arcsec()};
}

// The rows of the fit (twin_calibrator.hpp), from the replay of the parameters they correct.
struct FitRows {
  std::vector<double> th1, th2, target, flank, twist, torque, speed;
  void clear() { *this = FitRows{}; }
};

// Rows from a replay's points with `params` (the replayed ones).
PointSink row_sink(FitRows& rows, const model::GearParams& params,
                   const metrology::GearSense& sense) {
  const double half = 0.5 * params.backlash.total_rad;
  std::shared_ptr<model::ElasticStiffness> law;
  if (model::is_elastic(params.stiffness.law)) {
    law = std::make_shared<model::ElasticStiffness>(params.stiffness);
  }
  const double ratio = sense.ratio;
  return [&rows, half, law, ratio](const TwinPoint& p) {
    if (!std::isfinite(p.measured_te_rad) || !std::isfinite(p.predicted_te_rad) ||
        !std::isfinite(p.theta2_rad) || !std::isfinite(p.twist_rad)) {
      return;
    }
    rows.th1.push_back(p.theta1_rad);
    rows.th2.push_back(p.theta2_rad);
    rows.target.push_back(p.predicted_te_rad - p.measured_te_rad);  // δe + flank·δb/2 + δx
    rows.flank.push_back(p.twist_rad > half ? 0.5 : (p.twist_rad < -half ? -0.5 : 0.0));
    rows.twist.push_back(p.spring_twist_rad);
    rows.torque.push_back(law ? std::copysign(law->torque_unmodulated(std::abs(p.spring_twist_rad)),
                                              p.spring_twist_rad)
                              : p.gear_torque_nm);
    rows.speed.push_back(p.omega1_rad_s / ratio);
  };
}

// Every run replayed; with `rows`, their fit rows too (run after run).
std::vector<Replay> replay_all(const model::GearParams& params, const metrology::GearSense& sense,
                               std::span<const std::span<const storage::SyncSample>> runs,
                               const TwinSolverOptions& solver, FitRows* rows = nullptr) {
  std::vector<Replay> out;
  out.reserve(runs.size());
  const PointSink sink = rows != nullptr ? row_sink(*rows, params, sense) : PointSink{};
  for (const auto& samples : runs) out.push_back(replay(params, sense, samples, solver, sink));
  return out;
}

// RMS of the residual over every run's samples together (each run weighs what it measured).
double pooled_rms(const std::vector<Replay>& replays) {
  double squares = 0, n = 0;
  for (const auto& r : replays) {
    const auto m = static_cast<double>(r.residual.samples);
    squares += r.residual.rms_arcsec * r.residual.rms_arcsec * m;
    n += m;
  }
  return n > 0 ? std::sqrt(squares / n) : std::numeric_limits<double>::infinity();
}

// The three segments' compliance columns of a catalogue curve: the twist is
// c1·min(|T|, T1) + c2·clamp(|T| − T1, 0, T2 − T1) + c3·max(|T| − T2, 0) (signed), linear in the
// compliances c = 1/K with T1 and T2 held. `covered` says whether each segment holds enough
// rows (min_fraction of them well inside it) for its compliance to be told from the others'.
struct SegmentColumns {
  std::array<std::vector<double>, 3> columns;
  std::array<bool, 3> covered{};
};
SegmentColumns segment_columns(const model::ThreeSegmentStiffness& k,
                               const std::vector<double>& torque, double min_fraction) {
  SegmentColumns out;
  std::array<std::size_t, 3> inside{};
  for (const double t : torque) {
    const double a = std::abs(t);
    out.columns[0].push_back(std::copysign(std::min(a, k.t1), t));
    out.columns[1].push_back(std::copysign(std::clamp(a - k.t1, 0.0, k.t2 - k.t1), t));
    out.columns[2].push_back(std::copysign(std::max(a - k.t2, 0.0), t));
    if (a > 0.1 * k.t1 && a < 0.9 * k.t1) ++inside[0];
    if (a > k.t1 + 0.1 * (k.t2 - k.t1) && a < k.t2 - 0.1 * (k.t2 - k.t1)) ++inside[1];
    if (a > 1.1 * k.t2) ++inside[2];
  }
  const double need = min_fraction * static_cast<double>(torque.size());
  for (std::size_t i = 0; i < 3; ++i) out.covered[i] = static_cast<double>(inside[i]) >= need;
  return out;
}

void note_fitted(std::vector<std::string>& fitted, const std::string& name) {
  if (std::find(fitted.begin(), fitted.end(), name) == fitted.end()) fitted.push_back(name);
}

// What the fit over one or several runs arrives at.
struct JointFit {
  std::vector<Replay> before;  // the nominal twin, per run (when fitted against it)
  std::vector<Replay> best;    // the calibrated twin, per run
  std::vector<std::string> fitted;
  std::vector<HarmonicOrder> orders;
  int passes = 0;
};

// The calibration (twin_calibrator.hpp) over the rows of every run in one solve: the runs
// share the gear (harmonics, offset, backlash, stiffness) and the bench (input latch delay).
// `start` is where the parameters begin (an estimate from a static run or a torsional loop);
// `start_fitted` names what set it. With `against_nominal` the nominal twin is replayed too
// (`before`) and stays the calibration when nothing beats it; otherwise the start is the
// baseline (a unit's twin over several runs: the replays cost what the runs measured).
JointFit fit_jointly(const model::GearParams& nominal, const model::GearParams& start,
                     const std::string& start_fitted, const metrology::GearSense& sense,
                     std::span<const std::span<const storage::SyncSample>> runs,
                     const TwinCalibrationOptions& options, bool against_nominal) {
  JointFit out;
  model::GearParams params = start;
  TwinSolverOptions solver = options.solver;
  if (!start_fitted.empty()) out.fitted.push_back(start_fitted);
  std::vector<Replay> best;
  std::vector<Replay> current;
  FitRows rows;  // from the replay of `params`, the current parameters
  if (against_nominal) {
    out.before =
        replay_all(nominal, sense, runs, options.solver, start_fitted.empty() ? &rows : nullptr);
    best = out.before;
    current = best;
    if (!start_fitted.empty()) {
      current = replay_all(params, sense, runs, solver, &rows);
      // With passes = 0 the estimate alone is the calibration; otherwise the best replay wins.
      if (options.passes == 0 || pooled_rms(current) < pooled_rms(best)) best = current;
    }
  } else {
    current = replay_all(params, sense, runs, solver, &rows);
    best = current;
  }

  const auto candidates = candidate_orders(nominal, options.extra_orders);
  for (int pass = 0; pass < options.passes; ++pass) {
    const auto& th1 = rows.th1;
    const auto& th2 = rows.th2;
    const auto& target = rows.target;
    const auto& flank = rows.flank;
    const auto& twist = rows.twist;
    const auto& torque = rows.torque;
    const auto& speed = rows.speed;
    const std::size_t n = target.size();
    if (n == 0) break;
    // The basis the runs resolve together.
    std::vector<HarmonicOrder> orders;
    for (const auto& o : candidates) {
      double lo = INFINITY, hi = -INFINITY;
      for (std::size_t i = 0; i < n; ++i) {
        const double u = o.order_input * th1[i] + o.order_output * th2[i];
        lo = std::min(lo, u);
        hi = std::max(hi, u);
      }
      if (hi - lo >= options.min_phase_span_rad) orders.push_back(o);
    }
    std::vector<std::vector<double>> regressors;
    std::vector<std::string> names;
    std::vector<double> scales;
    const auto add_scaled = [&](std::vector<double> column, const std::string& name) {
      double squares = 0;
      for (const double v : column) squares += v * v;
      const double scale = std::sqrt(squares / static_cast<double>(n));
      if (!(scale > 0)) return;
      for (double& v : column) v /= scale;  // a column of order 1, like the others
      regressors.push_back(std::move(column));
      names.push_back(name);
      scales.push_back(scale);
    };
    const auto upper = static_cast<double>(std::count(flank.begin(), flank.end(), 0.5));
    const auto lower = static_cast<double>(std::count(flank.begin(), flank.end(), -0.5));
    const double need = options.min_flank_fraction * static_cast<double>(n);
    if (upper >= need && lower >= need) add_scaled(flank, "backlash");
    // Stiffness: each segment of a catalogue curve on its own where the runs load every
    // segment (a locked-output loop does), else one factor on the whole law.
    auto* segments = std::get_if<model::ThreeSegmentStiffness>(&params.stiffness.law);
    bool per_segment = false;
    if (segments != nullptr) {
      auto columns = segment_columns(*segments, torque, options.min_segment_fraction);
      per_segment = columns.covered[0] && columns.covered[1] && columns.covered[2];
      if (per_segment) {
        for (std::size_t i = 0; i < 3; ++i) {
          add_scaled(std::move(columns.columns[i]), "compliance_k" + std::to_string(i + 1));
        }
      }
    }
    if (!per_segment && percentile_span(torque, 0.02) >= options.min_torque_span_nm) {
      add_scaled(twist, "stiffness");
    }
    // With the speed's sign always the flank's (runs that only move), the delay and the
    // backlash cannot be told apart: the backlash is the gear's, so it wins.
    const bool apart_from_flank = std::abs(correlation(speed, flank)) < 0.9;
    if (percentile_span(speed, 0.02) >= options.min_speed_span_rad_s && apart_from_flank) {
      add_scaled(speed, "input_latch_delay");
    }
    const auto fit = metrology::fit_te_harmonics(th1, th2, target, orders, regressors);
    for (const auto& h : fit.fit.harmonics) merge_harmonic(params.te_terms, h);
    merge_offset(params.te_terms, fit.fit.offset_rad);
    for (std::size_t r = 0; r < names.size(); ++r) {
      const double c = fit.coefficients[r] / scales[r];
      if (names[r] == "backlash") {
        params.backlash.total_rad = std::max(0.0, params.backlash.total_rad + c);
      } else if (names[r] == "input_latch_delay") {
        // pred − meas = −δ·ω1/N: the delay grows by −c.
        solver.input_latch_delay_s -= c;
      } else if (names[r] == "stiffness") {
        // x → (1 + ε)·x under the same torque: k → k/(1 + ε); kept within a factor of 5.
        model::scale_stiffness(params.stiffness, 1.0 / (1.0 + std::clamp(c, -0.8, 4.0)));
      } else {
        // Compliance 1/K of segment i grows by c [rad/(N·m)]; K kept within a factor of 5.
        double* k = names[r] == "compliance_k1"   ? &segments->k1
                    : names[r] == "compliance_k2" ? &segments->k2
                                                  : &segments->k3;
        *k = std::clamp(1.0 / (1.0 / *k + c), 0.2 * *k, 5.0 * *k);
      }
    }
    note_fitted(out.fitted, "te_harmonics");
    note_fitted(out.fitted, "offset");
    for (const auto& name : names) {
      note_fitted(out.fitted, name.starts_with("compliance") ? "stiffness_per_segment" : name);
    }
    out.orders = orders;
    out.passes = pass + 1;
    rows.clear();
    current = replay_all(params, sense, runs, solver, pass + 1 < options.passes ? &rows : nullptr);
    if (pooled_rms(current) < pooled_rms(best)) best = current;
  }

  if (against_nominal && pooled_rms(best) >= pooled_rms(out.before) && options.passes > 0) {
    out.fitted.push_back("no_improvement");  // the nominal twin stays the best there is
  }
  out.best = std::move(best);
  return out;
}

}  // namespace

double small_twist_stiffness_ratio(const model::GearParams& nominal,
                                   const model::GearParams& calibrated) {
  if (!model::is_elastic(nominal.stiffness.law) || !model::is_elastic(calibrated.stiffness.law)) {
    return 1;
  }
  const double k0 = model::ElasticStiffness(nominal.stiffness).small_twist_stiffness();
  const double k1 = model::ElasticStiffness(calibrated.stiffness).small_twist_stiffness();
  return k0 > 0 ? k1 / k0 : 1;
}

double estimate_te_noise_floor_arcsec(std::span<const TwinPoint> points) {
  TwinOverlaySum sum;
  for (const auto& p : points) sum.add(p);
  return sum.noise_floor_arcsec();
}

TwinCalibration calibrate_twin(const model::GearParams& nominal, const metrology::GearSense& sense,
                               std::span<const storage::SyncSample> samples,
                               const metrology::StaticTeResult* static_run,
                               const TwinCalibrationOptions& options) {
  model::GearParams start = nominal;
  std::string start_fitted;
  if (static_run != nullptr) {
    try {
      const auto e = metrology::estimate_stiffness_backlash(*static_run);
      const double x = nominal_twist(start.stiffness, std::abs(e.load_nm));
      const double factor = x > 0 && std::abs(e.shift_rad) > 0 ? x / std::abs(e.shift_rad) : 0;
      // Only a plausible estimate seeds the fit (a factor of five either way at most).
      if (factor >= 0.2 && factor <= 5 && std::isfinite(e.backlash_rad)) {
        start.backlash.total_rad = std::abs(e.backlash_rad);
        model::scale_stiffness(start.stiffness, factor);
        start_fitted = "static_estimate";
      }
    } catch (const std::invalid_argument&) {
      // A static run without two loads or both directions: the sample fit alone decides.
    }
  }
  const std::array<std::span<const storage::SyncSample>, 1> runs{samples};
  JointFit fit = fit_jointly(nominal, start, start_fitted, sense, runs, options,
                             /*against_nominal=*/true);

  TwinCalibration cal;
  cal.nominal = nominal;
  cal.before = std::move(fit.before[0].residual);
  Replay& best = fit.best[0];
  cal.calibrated = best.params;
  cal.solver = best.solver;
  cal.calibrated.name = nominal.name + " (calibrated)";
  cal.after = std::move(best.residual);
  cal.noise_floor_arcsec = best.noise_floor_arcsec;
  cal.fitted = std::move(fit.fitted);
  cal.orders = std::move(fit.orders);
  cal.passes = fit.passes;
  cal.stiffness_factor = small_twist_stiffness_ratio(nominal, cal.calibrated);
  return cal;
}

UnitTwinCalibration calibrate_unit_twin(const model::GearParams& nominal,
                                        const metrology::GearSense& sense,
                                        std::span<const UnitRunSamples> runs,
                                        const UnitTwinStart& start_from,
                                        const TwinCalibrationOptions& options) {
  if (runs.empty()) throw std::invalid_argument("unit twin: no runs to calibrate from");
  model::GearParams start = nominal;
  std::string start_fitted;
  if (start_from.loop_stiffness) {
    const auto& k = *start_from.loop_stiffness;
    if (!(k.k1 > 0 && k.k2 > 0 && k.k3 > 0 && k.t1 > 0 && k.t2 > k.t1)) {
      throw std::invalid_argument(
          "unit twin: the torsional loop's K1/K2/K3 and T1/T2 are not a catalogue curve (expected "
          "K > 0 and 0 < T1 < T2)");
    }
    start.stiffness.law = k;
    start.stiffness.mean_stiffness.reset();
    start_fitted = "torsional_loop";
  }
  if (start_from.loop_backlash_rad && std::isfinite(*start_from.loop_backlash_rad)) {
    start.backlash.total_rad = std::abs(*start_from.loop_backlash_rad);
    start_fitted = "torsional_loop";
  }
  std::vector<std::span<const storage::SyncSample>> spans;
  for (const auto& r : runs) spans.push_back(r.samples);
  JointFit fit = fit_jointly(nominal, start, start_fitted, sense, spans, options,
                             /*against_nominal=*/false);

  UnitTwinCalibration cal;
  cal.nominal = nominal;
  cal.calibrated = fit.best[0].params;
  cal.calibrated.name = nominal.name + " (unit twin)";
  cal.solver = fit.best[0].solver;
  cal.fitted = std::move(fit.fitted);
  cal.orders = std::move(fit.orders);
  cal.passes = fit.passes;
  cal.stiffness_factor = small_twist_stiffness_ratio(nominal, cal.calibrated);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    UnitRunResidual r;
    r.run_id = runs[i].run_id;
    r.procedure = runs[i].procedure;
    r.samples = runs[i].samples.size();
    r.noise_floor_arcsec = fit.best[i].noise_floor_arcsec;
    r.after = std::move(fit.best[i].residual);
    cal.runs.push_back(std::move(r));
  }
  return cal;
}

std::uint64_t write_replay_csv(const std::filesystem::path& file, const model::GearParams& gear,
                               const metrology::GearSense& sense,
                               std::span<const storage::SyncSample> samples,
                               const TwinSolverOptions& solver) {
  TwinCsvWriter csv(file);
  replay(gear, sense, samples, solver, [&csv](const TwinPoint& p) { csv.add(p); });
  const auto rows = csv.rows();
  csv.commit();
  return rows;
}

void write_calibrated_twin_config(const std::filesystem::path& file,
                                  const TwinCalibration& calibration,
                                  const model::SimulationOptions& solver) {
  config::TwinCase twin;
  twin.gear = calibration.calibrated;
  twin.solver = solver;
  char line[256];
  std::snprintf(line, sizeof line,
                "Twin calibrated to a run (bench.md §5): residual RMS %.3f arcsec before, %.3f "
                "arcsec after.\nFitted: ",
                calibration.before.rms_arcsec, calibration.after.rms_arcsec);
  std::string comment = line;
  for (std::size_t i = 0; i < calibration.fitted.size(); ++i) {
    comment += (i ? ", " : "") + calibration.fitted[i];
  }
  comment += "\nFrom the nominal twin '" + calibration.nominal.name + "'.";
  storage::write_file_atomically(file, config::write_twin_case_yaml(twin, comment));
}

namespace {

nlohmann::json te_terms_json(const model::GearParams& gear) {
  nlohmann::json terms = nlohmann::json::array();
  for (const auto& t : gear.te_terms) {
    terms.push_back({{"source", t.source},
                     {"order_input", t.order_input},
                     {"order_output", t.order_output},
                     {"amplitude_arcsec", t.amplitude_rad * kArcsecPerRad},
                     {"phase_rad", t.phase_rad}});
  }
  return terms;
}

nlohmann::json stiffness_json(const model::GearParams& gear) {
  if (const auto* k = std::get_if<model::ThreeSegmentStiffness>(&gear.stiffness.law)) {
    return {{"form", "three_segment"}, {"k1_nm_per_rad", k->k1}, {"t1_nm", k->t1},
            {"k2_nm_per_rad", k->k2},  {"t2_nm", k->t2},         {"k3_nm_per_rad", k->k3}};
  }
  if (model::is_elastic(gear.stiffness.law)) {
    return {{"form", "other"},
            {"small_twist_nm_per_rad",
             model::ElasticStiffness(gear.stiffness).small_twist_stiffness()}};
  }
  return {{"form", "hysteretic"}};
}

}  // namespace

nlohmann::json to_json(const UnitTwinCalibration& c) {
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : c.runs) {
    runs.push_back({{"run_id", r.run_id},
                    {"procedure", r.procedure},
                    {"samples", r.samples},
                    {"rms_after_arcsec", r.after.rms_arcsec},
                    {"mean_after_arcsec", r.after.mean_arcsec},
                    {"noise_floor_arcsec", r.noise_floor_arcsec},
                    {"rms_after_over_noise_floor",
                     r.noise_floor_arcsec > 0 ? r.after.rms_arcsec / r.noise_floor_arcsec : 0.0}});
  }
  return {{"runs", runs},
          {"stiffness_nominal", stiffness_json(c.nominal)},
          {"stiffness", stiffness_json(c.calibrated)},
          {"stiffness_factor", c.stiffness_factor},
          {"backlash_nominal_arcmin", c.nominal.backlash.total_rad * kArcminPerRad},
          {"backlash_arcmin", c.calibrated.backlash.total_rad * kArcminPerRad},
          {"input_latch_delay_s", c.solver.input_latch_delay_s},
          {"fitted", c.fitted},
          {"passes", c.passes},
          {"te_terms", te_terms_json(c.calibrated)}};
}

nlohmann::json to_json(const TwinCalibration& c) {
  return {{"residual_before", metrology::to_json(c.before)},
          {"residual_after", metrology::to_json(c.after)},
          {"rms_before_arcsec", c.before.rms_arcsec},
          {"rms_after_arcsec", c.after.rms_arcsec},
          {"noise_floor_arcsec", c.noise_floor_arcsec},
          {"rms_after_over_noise_floor",
           c.noise_floor_arcsec > 0 ? c.after.rms_arcsec / c.noise_floor_arcsec : 0.0},
          {"backlash_nominal_arcmin", c.nominal.backlash.total_rad * kArcminPerRad},
          {"backlash_calibrated_arcmin", c.calibrated.backlash.total_rad * kArcminPerRad},
          {"stiffness_factor", c.stiffness_factor},
          {"input_latch_delay_s", c.solver.input_latch_delay_s},
          {"fitted", c.fitted},
          {"passes", c.passes},
          {"te_terms", te_terms_json(c.calibrated)}};
}

}  // namespace wavebench::twin
