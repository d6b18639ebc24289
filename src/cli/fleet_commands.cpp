// `wavebench fleet runs|trend|spc`: the lab's shared results store (issue #13), read directly
// with the daemon's `--results FILE` (or $WAVEBENCH_RESULTS_CONFIG), or a lone bench's own
// with `--runs DIR`. Tables on stdout, or JSON with --json. Exit 2 for a bad config or
// argument, 1 when the store cannot be reached.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"
#include "wavebench/report/figure.hpp"

namespace wavebench::cli {
namespace {

struct FleetArgs {
  std::string results, runs;
  std::string model, bench, unit, procedure, verdict, from, to, direction, figure;
  std::string load_nm, lsl, usl;  // numbers, parsed with their option's name in errors
  int limit = 50;
  int last = 0;
  bool json = false;
  std::string png;  // trend, spc: the chart as a PNG too
};

std::optional<std::string> given(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return text;
}

std::optional<double> number_option(const std::string& name, const std::string& text) {
  if (text.empty()) return std::nullopt;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(name + ": got '" + text + "', expected a number");
  }
  return value;
}

std::string results_file(const FleetArgs& args) {
  if (!args.results.empty()) return args.results;
  const char* env = std::getenv("WAVEBENCH_RESULTS_CONFIG");
  if (env && *env) return env;
  throw std::invalid_argument(
      "--results: not given, expected the results config (the daemon's --results FILE) or "
      "$WAVEBENCH_RESULTS_CONFIG");
}

fleet::FigureQuery figure_query(const FleetArgs& args) {
  fleet::FigureQuery q;
  q.figure = fleet::find_fleet_figure(args.figure).name;
  if (args.model.empty()) {
    throw std::invalid_argument("--model: not given, expected the gear model (a spec's model)");
  }
  q.gear_model = args.model;
  q.bench = given(args.bench);
  q.direction = given(args.direction);
  q.load_nm = number_option("--load", args.load_nm);
  q.from = given(args.from);
  q.to = given(args.to);
  q.last = args.last;
  return q;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string number(const std::optional<double>& v) {
  return v ? number(*v) : "-";
}

// The trend as an individuals chart: the values in run order, and with SPC its centre line,
// control limits and spec limits.
void write_chart(const std::string& path, const fleet::FleetFigure& figure,
                 const std::string& model, const std::vector<fleet::TrendPoint>& points,
                 const fleet::SpcAnswer* spc) {
  report::Figure chart(1, 1, std::string(figure.name) + " of " + model);
  auto& axes = chart.axes(0, 0);
  axes.title = spc ? "individuals chart" : "trend";
  axes.x_label = "run (oldest first)";
  axes.y_label = std::string(figure.name) + " [" + figure.unit + "]";
  std::vector<double> x, y;
  for (const auto& p : points) {
    x.push_back(p.sequence);
    y.push_back(p.value);
  }
  axes.line(x, y, "runs", report::palette(0));
  axes.scatter(x, y, {}, report::palette(0), 2.0);
  const double first = x.empty() ? 0 : x.front(), last = x.empty() ? 1 : x.back();
  const auto level = [&](double value, const std::string& label, int color) {
    axes.line({first, last}, {value, value}, label, report::palette(color));
  };
  if (spc && points.size() >= 2) {
    level(spc->figures.mean, "mean", 1);
    level(spc->figures.ucl, "UCL (mean + 2.66 MR-bar)", 2);
    level(spc->figures.lcl, "LCL", 2);
    if (spc->limits.upper) level(*spc->limits.upper, "upper spec limit", 3);
    if (spc->limits.lower) level(*spc->limits.lower, "lower spec limit", 3);
  }
  chart.write_png(path);
}

void print_runs(fleet::ResultsStore& store, const FleetArgs& args) {
  fleet::FleetRunQuery q;
  q.gear_model = given(args.model);
  q.bench = given(args.bench);
  q.unit_serial = given(args.unit);
  q.procedure = given(args.procedure);
  q.verdict = given(args.verdict);
  q.from = given(args.from);
  q.to = given(args.to);
  q.limit = args.limit;
  const auto rows = store.runs(q);
  if (args.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& r : rows) out.push_back(fleet::to_json(r));
    std::cout << nlohmann::json{{"runs", out}}.dump(2) << "\n";
    return;
  }
  std::printf("%-12s %-24s %-28s %-16s %-20s %-11s %-9s %s\n", "bench", "run", "started", "unit",
              "model", "procedure", "verdict", "figures");
  for (const auto& r : rows) {
    std::string figures;
    for (const auto& [name, value] : r.figures.items()) {
      figures += (figures.empty() ? "" : " ") + name + "=" + number(value.get<double>());
    }
    std::printf("%-12s %-24s %-28s %-16s %-20s %-11s %-9s %s\n", r.bench.c_str(), r.run_id.c_str(),
                r.started_at.c_str(), r.unit_serial.c_str(), r.gear_model.c_str(),
                r.procedure.c_str(), r.verdict.empty() ? "-" : r.verdict.c_str(), figures.c_str());
  }
}

void print_trend(fleet::ResultsStore& store, const FleetArgs& args) {
  const auto q = figure_query(args);
  const auto points = store.trend(q);
  const auto& figure = fleet::find_fleet_figure(q.figure);
  if (!args.png.empty()) write_chart(args.png, figure, q.gear_model, points, nullptr);
  if (args.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : points) out.push_back(fleet::to_json(p));
    std::cout << nlohmann::json{{"figure", figure.name},
                                {"unit", figure.unit},
                                {"gear_model", q.gear_model},
                                {"points", out}}
                     .dump(2)
              << "\n";
    return;
  }
  std::printf("%s [%s] of %s: %zu runs, oldest first\n", figure.name, figure.unit,
              q.gear_model.c_str(), points.size());
  std::printf("%6s %-28s %-12s %-24s %-16s %s\n", "seq", "started", "bench", "run", "unit",
              "value");
  for (const auto& p : points) {
    std::printf("%6d %-28s %-12s %-24s %-16s %s\n", p.sequence, p.started_at.c_str(),
                p.bench.c_str(), p.run_id.c_str(), p.unit_serial.c_str(), number(p.value).c_str());
  }
}

void print_spc(fleet::ResultsStore& store, const FleetArgs& args) {
  const auto q = figure_query(args);
  fleet::SpecLimits limits{number_option("--lsl", args.lsl), number_option("--usl", args.usl)};
  if (limits.lower && limits.upper && !(*limits.lower < *limits.upper)) {
    throw std::invalid_argument("--lsl: got '" + args.lsl + "', expected below --usl (" +
                                args.usl + ")");
  }
  const auto answer = store.spc(q, limits);
  const auto& figure = fleet::find_fleet_figure(q.figure);
  if (!args.png.empty()) write_chart(args.png, figure, q.gear_model, answer.points, &answer);
  if (args.json) {
    auto j = fleet::to_json(answer);
    j["figure"] = figure.name;
    j["unit"] = figure.unit;
    j["gear_model"] = q.gear_model;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("%s [%s] of %s: %zu runs; limits from %s: lower %s, upper %s\n", figure.name,
              figure.unit, q.gear_model.c_str(), answer.points.size(), answer.limits_from.c_str(),
              number(answer.limits.lower).c_str(), number(answer.limits.upper).c_str());
  if (answer.points.size() < 2) {
    std::printf("fewer than 2 runs: no SPC\n");
    return;
  }
  const auto& s = answer.figures;
  std::printf("mean %s  sigma %s  MR-bar %s  sigma within %s\n", number(s.mean).c_str(),
              number(s.sigma).c_str(), number(s.mr_bar).c_str(), number(s.sigma_within).c_str());
  std::printf("individuals chart: UCL %s  CL %s  LCL %s  (%zu points outside)\n",
              number(s.ucl).c_str(), number(s.mean).c_str(), number(s.lcl).c_str(),
              s.out_of_control.size());
  std::printf("Cp %s  Cpk %s  (within)   Pp %s  Ppk %s  (overall)\n", number(s.cp).c_str(),
              number(s.cpk).c_str(), number(s.pp).c_str(), number(s.ppk).c_str());
  for (const auto i : s.out_of_control) {
    const auto& p = answer.points[i];
    std::printf("  outside: #%d %s %s %s = %s\n", p.sequence, p.bench.c_str(), p.run_id.c_str(),
                p.unit_serial.c_str(), number(p.value).c_str());
  }
}

// --runs DIR: the bench's own store in DIR/index.sqlite, read only (the daemon writes it).
template <typename Print>
int with_store(const FleetArgs& args, Print print) {
  fleet::ResultsConfig config;
  if (!args.runs.empty() && !args.results.empty()) {
    std::cerr << "wavebench fleet: --runs and --results: both given, expected one store\n";
    return 2;
  }
  if (args.runs.empty()) {
    try {
      const std::string file = results_file(args);
      config = fleet::load_results_config(file);
      if (!config.shared()) {
        throw std::invalid_argument("results.store: got 'sqlite' in " + file +
                                    ", expected postgresql (a shared store to query), or "
                                    "--runs DIR for a bench's own store");
      }
    } catch (const std::exception& e) {
      std::cerr << "wavebench fleet: " << e.what() << "\n";
      return 2;
    }
  } else if (!std::filesystem::is_regular_file(std::filesystem::path(args.runs) / "index.sqlite")) {
    std::cerr << "wavebench fleet: --runs: got '" << args.runs
              << "', expected a run store folder (holding index.sqlite)\n";
    return 2;
  }
  std::unique_ptr<fleet::ResultsStore> store;
  try {
    if (args.runs.empty()) {
      store = std::make_unique<fleet::PostgresResultsStore>(config);
    } else {
      store = std::make_unique<fleet::SqliteResultsStore>(
          std::filesystem::path(args.runs) / "index.sqlite",
          fleet::SqliteResultsStore::Access::kReadOnly);
    }
  } catch (const std::exception& e) {
    std::cerr << "wavebench fleet: " << e.what() << "\n";
    return 1;
  }
  try {
    print(*store, args);
  } catch (const std::invalid_argument& e) {
    std::cerr << "wavebench fleet: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "wavebench fleet: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

void add_common(CLI::App* cmd, FleetArgs& args) {
  cmd->add_option("--results", args.results,
                  "results config (results: {store: postgresql, url, password_file}); default "
                  "$WAVEBENCH_RESULTS_CONFIG");
  cmd->add_option("--runs", args.runs,
                  "a bench's own store instead: its run store folder (wavebenchd --runs DIR)");
  cmd->add_option("--bench", args.bench, "only this bench");
  cmd->add_option("--from", args.from, "started at or after (ISO 8601, e.g. 2026-11-01)");
  cmd->add_option("--to", args.to, "started at or before (ISO 8601)");
  cmd->add_flag("--json", args.json, "JSON instead of a table");
}

void add_figure(CLI::App* cmd, FleetArgs& args) {
  std::string names;
  for (const auto& f : fleet::fleet_figures())
    names += std::string(names.empty() ? "" : ", ") + f.name;
  cmd->add_option("--figure", args.figure, "the figure: " + names)->required();
  cmd->add_option("--model", args.model, "the gear model (a spec's model)")->required();
  cmd->add_option("--direction", args.direction, "static_te_p2p: one direction (forward|reverse)");
  cmd->add_option("--load", args.load_nm, "static_te_p2p: one load [N*m]");
  cmd->add_option("--last", args.last, "only the newest N runs")->check(CLI::NonNegativeNumber);
  cmd->add_option("--png", args.png, "also draw the chart into this PNG file");
}

}  // namespace

void register_fleet_commands(CLI::App& app, ExitStatus& status) {
  CLI::App* fleet_cmd =
      app.add_subcommand("fleet", "the lab's shared results store: runs, trends and SPC");
  fleet_cmd->require_subcommand(1);

  auto runs_args = std::make_shared<FleetArgs>();
  CLI::App* runs = fleet_cmd->add_subcommand("runs", "runs of every bench, newest first");
  add_common(runs, *runs_args);
  runs->add_option("--model", runs_args->model, "only this gear model");
  runs->add_option("--unit", runs_args->unit, "only this unit serial");
  runs->add_option("--procedure", runs_args->procedure, "only this procedure");
  runs->add_option("--verdict", runs_args->verdict, "PASS, FAIL or UNDECIDED");
  runs->add_option("--limit", runs_args->limit, "at most N runs")->check(CLI::Range(1, 100000));
  runs->callback([runs_args, &status] { status.code = with_store(*runs_args, print_runs); });

  auto trend_args = std::make_shared<FleetArgs>();
  CLI::App* trend =
      fleet_cmd->add_subcommand("trend", "one figure of a gear model over its runs, oldest first");
  add_common(trend, *trend_args);
  add_figure(trend, *trend_args);
  trend->callback([trend_args, &status] { status.code = with_store(*trend_args, print_trend); });

  auto spc_args = std::make_shared<FleetArgs>();
  CLI::App* spc = fleet_cmd->add_subcommand(
      "spc", "mean, sigma, Cp/Cpk and the individuals chart of one figure of a gear model");
  add_common(spc, *spc_args);
  add_figure(spc, *spc_args);
  spc->add_option("--lsl", spc_args->lsl, "lower spec limit (default: the newest run's spec)");
  spc->add_option("--usl", spc_args->usl, "upper spec limit (default: the newest run's spec)");
  spc->callback([spc_args, &status] { status.code = with_store(*spc_args, print_spc); });
}

}  // namespace wavebench::cli
