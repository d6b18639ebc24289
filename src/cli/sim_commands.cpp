// `wavebench twin CONFIG --out DIR`: run a twin case, analyse it, write CSV, JSON and plots.
// Output goes to a temporary sibling of DIR that is renamed into place at the end, so DIR is
// either complete or absent; a bad config writes nothing at all. DIR must be new, empty or an
// earlier sim's output (sim_output_folder.hpp); a signal removes the temporary folder.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>

#include "commands.hpp"
#include "sim_output_folder.hpp"
#include "stop_signals.hpp"
#include "wavebench/analysis/twin_analysis.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/report/timeseries_csv.hpp"
#include "wavebench/report/twin_plots.hpp"

namespace wavebench::cli {
namespace {

namespace fs = std::filesystem;
constexpr double kRpmPerRadS = 60.0 / (2.0 * std::numbers::pi);

struct SimArgs {
  std::string config;
  std::string out;
  std::optional<double> t_end;
  bool quiet = false;
};

// Progress on stderr for runs that take a while; quiet for short ones.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled) : enabled_(enabled), start_(Clock::now()) {}
  void update(double fraction) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < 1.0 || fraction < next_ || elapsed < last_ + 0.5) return;
    next_ = fraction + 0.01;
    last_ = elapsed;
    std::fprintf(stderr, "\rsimulating: %3.0f %%  (%.1f s)", 100 * std::min(fraction, 1.0),
                 elapsed);
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (shown_) std::fprintf(stderr, "\rsimulating: done                      \n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_;
  double next_ = 0;
  double last_ = 0;
  bool shown_ = false;
};

std::string unit_of(const std::string& signal) {
  if (signal == "alpha2") return "rad/s^2";
  if (signal == "omega1" || signal == "omega2" || signal == "twist_rate") return "rad/s";
  if (signal == "te" || signal == "twist" || signal == "theta2_dev") return "rad";
  if (signal.find("torque") != std::string::npos) return "N*m";
  return "";
}

// "dF_i1 (Flexspline tangential composite error)" -> "dF_i1": labels on plots stay short.
std::string short_source(const std::string& source) {
  const auto cut = source.find(" (");
  return cut == std::string::npos ? source : source.substr(0, cut);
}

std::vector<report::NamedPeak> named_peaks(const analysis::TwinAnalysis& a) {
  std::vector<report::NamedPeak> out;
  for (const auto& p : a.peaks) {
    std::string label;
    for (std::size_t i = 0; i < p.sources.size() && i < 3; ++i) {
      label += (i ? ", " : "") + short_source(p.sources[i].source);
    }
    if (p.sources.size() > 3) label += ", ...";
    if (label.empty() && p.label != "te") label = p.label;
    out.push_back({p.frequency_hz, p.amplitude, label});
  }
  return out;
}

// The last few dozen periods of the largest line: a whole record only fills the plane. Twist
// against its rate shows the mesh (the TE's own rate is in it); output angle against output
// speed, both relative to the nominal motion, shows how the output mass moves.
std::vector<report::PortraitPanel> portrait_panels(const model::SampledResponse& r,
                                                   const analysis::TwinAnalysis& a) {
  std::size_t first = 0;
  if (!a.peaks.empty() && a.peaks.front().frequency_hz > 0 && r.t.size() > 1) {
    const double span = 40.0 / a.peaks.front().frequency_hz;
    const double t0 = r.t.back() - span;
    first = static_cast<std::size_t>(std::lower_bound(r.t.begin(), r.t.end(), t0) - r.t.begin());
  }
  report::PortraitPanel twist{
      "Twist against twist rate", "twist [arcsec]", "twist rate [arcsec/s]", {}, {}};
  report::PortraitPanel output{"Output relative to the nominal motion",
                               "theta2 - theta1_nom/N [arcsec]",
                               "omega2 - mean [arcsec/s]",
                               {},
                               {}};
  double mean_w2 = 0;
  for (std::size_t i = first; i < r.omega2.size(); ++i) mean_w2 += r.omega2[i];
  if (r.omega2.size() > first) mean_w2 /= static_cast<double>(r.omega2.size() - first);
  const std::size_t n = r.t.size();
  for (std::size_t i = first; i < n; ++i) {
    if (i < r.twist.size() && i < r.twist_rate.size()) {
      twist.x.push_back(r.twist[i] * model::kArcsecPerRad);
      twist.v.push_back(r.twist_rate[i] * model::kArcsecPerRad);
    }
    if (i < r.theta2_dev.size() && i < r.omega2.size()) {
      output.x.push_back(r.theta2_dev[i] * model::kArcsecPerRad);
      output.v.push_back((r.omega2[i] - mean_w2) * model::kArcsecPerRad);
    }
  }
  return {twist, output};
}

void write_plots(const fs::path& dir, const config::TwinCase& twin,
                 const model::SimulationResult& result, const analysis::TwinAnalysis& a) {
  const std::string name = twin.gear.name.empty() ? "twin" : twin.gear.name;
  const auto& r = result.response;
  // Zoom on a few periods of the largest line, or 50 ms.
  double zoom = 0.05;
  if (!a.peaks.empty() && a.peaks.front().frequency_hz > 0) {
    zoom = std::clamp(5.0 / a.peaks.front().frequency_hz, 1e-3, 1.0);
  }
  report::time_response_figure(r, name + ": time response", zoom)
      .write_png(dir / "time_response.png");

  const std::string unit = unit_of(a.signal);
  report::spectrum_figure(a.spectrum.frequency_hz, a.spectrum.amplitude, named_peaks(a),
                          a.signal + (unit.empty() ? "" : " [" + unit + "]"),
                          name + ": spectrum of " + a.signal)
      .write_png(dir / "spectrum.png");

  report::phase_portrait_figure(portrait_panels(r, a), name + ": phase portraits")
      .write_png(dir / "phase_portrait.png", 1600, 750);

  std::vector<double> px, pv;
  for (const auto& p : a.poincare.points) {
    px.push_back(p.x * model::kArcsecPerRad);
    pv.push_back(p.v * model::kArcsecPerRad);
  }
  report::poincare_figure(
      px, pv, "twist [arcsec]", "twist rate [arcsec/s]",
      analysis::motion_class_name(a.motion.motion),
      name + ": Poincare section, strobed by " + short_source(a.poincare.excitation_source))
      .write_png(dir / "poincare.png", 1000, 800);

  if (a.sweep) {
    auto branch = [&](const std::vector<analysis::SweepPoint>& pts, const char* label) {
      report::SweepBranch b;
      b.label = label;
      for (const auto& p : pts) {
        b.speed_rpm.push_back(p.speed * kRpmPerRadS);
        b.amplitude.push_back(p.amplitude);
        std::vector<double> vals;
        for (const double d : p.poincare_x) vals.push_back(d * model::kArcsecPerRad);
        b.section_values.push_back(vals);
      }
      return b;
    };
    // Only the few largest jumps get a label; small relative jumps at low amplitude would
    // bury the plot in text.
    auto ranked = a.sweep->jumps;
    std::sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) {
      return std::abs(x.to_amplitude - x.from_amplitude) >
             std::abs(y.to_amplitude - y.from_amplitude);
    });
    std::vector<double> jumps;
    for (const auto& j : ranked) {
      const double rpm = j.to_speed * kRpmPerRadS;
      if (jumps.size() < 4 && std::find(jumps.begin(), jumps.end(), rpm) == jumps.end()) {
        jumps.push_back(rpm);
      }
    }
    report::bifurcation_figure(
        {branch(a.sweep->up, "sweep up"), branch(a.sweep->down, "sweep down")},
        "twist at the section [arcsec]",
        a.signal + " amplitude" + (unit.empty() ? "" : " [" + unit + "]"), jumps,
        name + ": speed sweep")
        .write_png(dir / "bifurcation.png");
  }
}

void print_summary(const config::TwinCase& twin, const model::SimulationResult& result,
                   const analysis::TwinAnalysis& a, double total_wall_s) {
  const auto& st = result.stats;
  std::printf("%s\n", twin.gear.name.empty() ? "twin run" : twin.gear.name.c_str());
  std::printf(
      "  simulated %.3g s (record %.3g s at %.0f Hz): %lld steps, %lld rhs evaluations,"
      " %lld events, solver %.2f s, total %.2f s\n",
      twin.solver.t_end,
      result.response.t.size() > 1 ? result.response.t.back() - result.response.t.front() : 0.0,
      twin.solver.sample_rate, static_cast<long long>(st.steps),
      static_cast<long long>(st.rhs_evaluations), static_cast<long long>(st.events), st.wall_s,
      total_wall_s);
  const std::string unit = unit_of(a.signal);
  std::printf("  peaks of %s%s:\n", a.signal.c_str(),
              unit.empty() ? "" : (" [" + unit + "]").c_str());
  std::printf("    %12s  %12s  %s\n", "freq [Hz]", "amplitude", "sources (share)");
  for (const auto& p : a.peaks) {
    std::string sources;
    for (std::size_t i = 0; i < p.sources.size() && i < 4; ++i) {
      char buf[24];
      std::snprintf(buf, sizeof buf, " %.0f%%", 100 * p.sources[i].share);
      sources += (i ? ", " : "") + short_source(p.sources[i].source) + buf;
    }
    if (sources.empty()) sources = p.label;
    if (p.aliased) sources += " [aliased]";
    std::printf("    %12.3f  %12.4g  %s\n", p.frequency_hz, p.amplitude, sources.c_str());
  }
  std::printf("  motion: %s - %s\n", analysis::motion_class_name(a.motion.motion),
              a.motion.summary.c_str());
  if (a.linear && !a.linear->modes.empty()) {
    std::printf("  natural frequencies:");
    for (const auto& m : a.linear->modes) std::printf(" %.2f Hz", m.natural_frequency_hz);
    std::printf("\n");
  }
}

int run_sim(const SimArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  config::TwinCase twin;
  try {
    twin = config::load_twin_case(args.config);
  } catch (const config::ConfigError& e) {
    std::cerr << "wavebench twin: " << e.what() << "\n";
    return 2;
  }
  if (args.t_end) {
    if (!(std::isfinite(*args.t_end) && *args.t_end >= config::kMinTwinSimulatedS &&
          *args.t_end <= config::kMaxTwinSimulatedS)) {
      std::cerr << "wavebench twin: --t-end: got '" << *args.t_end
                << "', expected a time in seconds in [" << config::kMinTwinSimulatedS << ", "
                << config::kMaxTwinSimulatedS << "]\n";
      return 2;
    }
    twin.solver.t_end = *args.t_end;
    if (twin.solver.transient >= twin.solver.t_end) {
      // A short trial run keeps half of itself rather than nothing.
      twin.solver.transient = 0.5 * twin.solver.t_end;
      if (!args.quiet) {
        std::cerr << "wavebench twin: transient shortened to " << twin.solver.transient
                  << " s to fit --t-end\n";
      }
    }
  }
  // A sweep in a short trial run would still take its full time: --t-end means "quick".
  if (args.t_end && twin.analysis.sweep.enabled) {
    const auto& sw = twin.analysis.sweep;
    const double sweep_time = 2.0 * sw.steps * (sw.settle_time + sw.record_time);
    if (sweep_time > 4 * *args.t_end) {
      twin.analysis.sweep.enabled = false;
      if (!args.quiet) std::cerr << "wavebench twin: speed sweep skipped for the short run\n";
    }
  }
  if (args.t_end) {
    try {
      config::check_twin_run_budget(twin, "--t-end");
    } catch (const config::ConfigError& e) {
      std::cerr << "wavebench twin: " << e.what() << "\n";
      return 2;
    }
  }

  fs::path out = fs::absolute(fs::path(args.out)).lexically_normal();
  if (out.filename().empty()) out = out.parent_path();  // "dir/" names dir
  if (const auto refusal = sim_output_refusal(out)) {
    std::cerr << "wavebench twin: --out: got '" << args.out << "', expected a new folder, an "
              << "empty one or an earlier wavebench twin output: " << *refusal << "\n";
    return 2;
  }
  remove_stale_sim_temp_folders(out);
  const fs::path tmp = sim_temp_folder(out);
  StopSignals stop;
  try {
    ProgressLine progress(!args.quiet);
    twin.solver.progress = [&progress](double f) {
      StopSignals::throw_if_requested();
      progress.update(f);
    };
    const model::SimulationResult result = model::simulate(twin.gear, twin.solver);
    progress.finish();
    try {
      config::check_finite_response(result.response);
    } catch (const config::ConfigError& e) {
      std::cerr << "wavebench twin: " << e.with_source(args.config).what() << "\n";
      return 2;
    }
    // A sweep in the analysis simulates again, silently, but still stops on a signal.
    twin.solver.progress = [](double) { StopSignals::throw_if_requested(); };
    if (!args.quiet) std::cerr << "analysing ...\n";
    const analysis::TwinAnalysis a =
        analysis::analyse_twin_run(twin.gear, twin.solver, result, twin.analysis);
    StopSignals::throw_if_requested();

    fs::create_directories(out.parent_path());
    fs::create_directory(tmp);
    write_sim_marker(tmp, fs::absolute(args.config).string());
    report::write_timeseries_csv(tmp / "timeseries.csv", result.response);
    StopSignals::throw_if_requested();
    write_plots(tmp, twin, result, a);
    StopSignals::throw_if_requested();
    const double total_wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json summary = analysis::summary_json(a, result);
    summary["case"] = twin.gear.name;
    summary["config"] = fs::absolute(args.config).string();
    summary["t_end_s"] = twin.solver.t_end;
    summary["transient_s"] = twin.solver.transient;
    summary["total_wall_s"] = total_wall;
    {
      std::ofstream json(tmp / "summary.json");
      json << summary.dump(2) << "\n";
      if (!json) throw std::runtime_error("cannot write summary.json");
    }
    StopSignals::throw_if_requested();
    move_sim_output_into_place(tmp, out);
    print_summary(twin, result, a, total_wall);
    std::printf("  written: %s\n", out.c_str());
  } catch (const StopRequested&) {
    remove_sim_output(tmp);
    std::cerr << "\nwavebench twin: stopped by a signal; " << out.string() << " left as it was\n";
    stop.reraise();
  } catch (const std::exception& e) {
    // Also std::bad_alloc: the budgets should make it impossible, but never leave a temp folder.
    remove_sim_output(tmp);
    std::cerr << "wavebench twin: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

void register_sim_commands(CLI::App& app, ExitStatus& status) {
  auto args = std::make_shared<SimArgs>();
  // `sim` is the name of the release before (issue #23): an alias for one more release.
  CLI::App* sim = app.add_subcommand("twin", "Run a digital-twin case and analyse it");
  sim->alias("sim");
  sim->add_option("config", args->config, "Twin-case YAML (configs/twin/*.yaml)")->required();
  sim->add_option("--out", args->out, "Directory for timeseries.csv, summary.json and plots")
      ->required();
  sim->add_option("--t-end", args->t_end, "Simulated time [s], overriding solver.t_end");
  sim->add_flag("--quiet", args->quiet,
                "No progress or notes on stderr (the summary still goes to stdout)");
  sim->callback([args, &status] { status.code = run_sim(*args); });
}

}  // namespace wavebench::cli
