// `wavebench run static|dynamic|lost-motion|torsional --bench simulated|CONFIG [--out DIR] ...`:
// one procedure without a daemon. Builds the bench (the in-process simulated bench for
// "simulated"), records the run in the store under --out, prints the summary table and where
// results and report are. A bad option or config, or a request the bench or the disk cannot take: a
// message naming the key, the value and what was expected, exit 2, nothing written.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "async_console_log.hpp"
#include "commands.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/fleet/run_summary.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"
#include "wavebench/procedures/procedure_catalogue.hpp"
#include "wavebench/procedures/procedure_options_file.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/procedures/run_request_check.hpp"
#include "wavebench/procedures/software_version.hpp"
#include "wavebench/report/run_report.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::cli {
namespace {

// The run summarised into the folder's own results store, as wavebenchd does at the end of
// every run, so that `wavebench fleet --runs DIR` and a daemon's fleet page see runs made
// without a daemon too. Idempotent by (bench, run id): a daemon started on the folder later
// finds it there and adds nothing. A failure here costs the summary only, never the run.
void summarise_into_own_store(const storage::RunStore& store,
                              const procedures::RunOutcome& outcome) {
  try {
    const auto record = store.find_run(outcome.run_id);
    if (!record) return;
    fleet::SqliteResultsStore own(store.root() / "index.sqlite");
    own.publish(fleet::summarise_run(*record, outcome.results, {}));
  } catch (const std::exception& e) {
    std::cerr << "wavebench run: warning: run " << outcome.run_id
              << " not summarised into the folder's results store (wavebenchd will on its start): "
              << e.what() << "\n";
  }
}

struct RunArgs {
  std::string procedure;
  std::string bench = "simulated";
  std::string out = "runs";
  std::optional<int> positions;
  std::vector<double> loads;
  std::optional<double> window;
  std::optional<double> rpm;
  std::optional<double> revolutions;
  std::optional<double> load;
  std::vector<double> torques;
  std::optional<int> repeats;        // any procedure
  std::string options_file;          // YAML procedure options (configs/procedures/*.yaml)
  std::vector<std::string> options;  // KEY=VALUE
  std::vector<std::string> limits;   // KEY=VALUE
  std::string spec;                  // a product spec's name (configs/specs/NAME.yaml)
  std::string specs_dir;             // empty: procedures::default_specs_dir()
  bool no_twin = false;
  bool no_report = false;
  bool no_calibration = false;
  bool quiet = false;
};

// VALUE as JSON when it parses (numbers, lists, true/false), else as a string.
nlohmann::json option_value(const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return text;
  }
}

void add_pairs(const std::vector<std::string>& pairs, const char* flag, nlohmann::json& into) {
  for (const auto& pair : pairs) {
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw std::invalid_argument(std::string(flag) + ": got '" + pair + "', expected KEY=VALUE");
    }
    into[pair.substr(0, eq)] = option_value(pair.substr(eq + 1));
  }
}

void only_for(bool given, const char* flag, const RunArgs& a, const char* procedure) {
  if (given && a.procedure != procedure) {
    throw std::invalid_argument(std::string(flag) + ": given for '" + a.procedure +
                                "', expected only with '" + procedure + "'");
  }
}

procedures::RunRequest build_request(const RunArgs& a) {
  procedures::RunRequest r;
  r.procedure = a.procedure;
  r.twin = !a.no_twin;
  r.report = !a.no_report;
  nlohmann::json o = nlohmann::json::object();
  if (!a.options_file.empty()) o = procedures::load_procedure_options(a.options_file);
  only_for(a.positions.has_value(), "--positions", a, "static");
  only_for(!a.loads.empty(), "--loads", a, "static");
  only_for(a.window.has_value(), "--window", a, "static");
  only_for(a.rpm.has_value(), "--rpm", a, "dynamic");
  only_for(a.revolutions.has_value(), "--revolutions", a, "dynamic");
  only_for(a.load.has_value(), "--load", a, "dynamic");
  only_for(!a.torques.empty(), "--torques", a, "lost-motion");
  if (a.positions) o["positions"] = *a.positions;
  if (!a.loads.empty()) o["loads_nm"] = a.loads;
  if (a.window) o["window_s"] = *a.window;
  if (a.rpm) o["input_rpm"] = *a.rpm;
  if (a.revolutions) o["output_revolutions"] = *a.revolutions;
  if (a.load) o["load_nm"] = *a.load;
  if (!a.torques.empty()) o["torques_nm"] = a.torques;
  if (a.repeats) o["repeats"] = *a.repeats;
  add_pairs(a.options, "--option", o);
  if (!a.limits.empty()) {
    nlohmann::json limits = nlohmann::json::object();
    add_pairs(a.limits, "--limit", limits);
    o["limits"] = limits;
  }
  if (a.no_calibration) o["calibrate_twin"] = false;
  r.options = o;
  if (!a.spec.empty()) {
    r.spec = procedures::find_product_spec(
        a.specs_dir.empty() ? procedures::default_specs_dir() : std::filesystem::path(a.specs_dir),
        a.spec);
  }
  return r;
}

// One line on stderr, rewritten as the run goes on.
class RunProgressLine {
 public:
  explicit RunProgressLine(bool enabled) : enabled_(enabled), start_(Clock::now()) {}
  void update(const procedures::RunProgress& p) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (p.phase == phase_ && elapsed < last_ + 0.5 && p.fraction < 1) return;
    phase_ = p.phase;
    last_ = elapsed;
    std::fprintf(stderr, "\r%-40.40s %3.0f %%  (%.0f s)", p.phase.c_str(), 100 * p.fraction,
                 elapsed);
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_;
  std::string phase_;
  double last_ = -1;
  bool shown_ = false;
};

int run_procedure(const RunArgs& a) {
  procedures::RunRequest request;
  bench::BenchConfig config;
  try {
    request = build_request(a);
    config = bench::bench_config_from_argument(a.bench);
    // The whole request against this bench and the runs folder, before anything is created
    // or moves: ranges, the bench's safety limits, duration and disk (issue #8).
    procedures::check_run_request(request, config.description, config.devices.size(), a.out);
  } catch (const config::ConfigError& e) {
    std::cerr << "wavebench run: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "wavebench run: " << e.what() << "\n";
    return 2;
  }
  request.config_text = config.text;

  const AsyncConsoleLog log;  // declared before the bench: outlives its threads
  std::unique_ptr<bench::Bench> bench;
  try {
    bench = bench::make_bench(config);
    bench->connect();
  } catch (const std::exception& e) {
    std::cerr << "wavebench run: bench '" << config.description.name
              << "' did not connect: " << e.what() << "\n";
    if (bench) bench->disconnect();
    return 1;
  }

  // After the connection (a bench that does not connect leaves no folder behind), before
  // anything moves: a folder another process writes runs into is refused.
  std::optional<storage::RunStore> store;
  try {
    store.emplace(a.out, procedures::software_version());
  } catch (const std::exception& e) {
    bench->disconnect();
    std::cerr << "wavebench run: --out " << a.out << ": " << e.what() << "\n";
    return 1;
  }
  RunProgressLine line(!a.quiet);
  procedures::RunOutcome outcome;
  try {
    outcome = procedures::execute_run(
        *bench, *store, request, [&line](const procedures::RunProgress& p) { line.update(p); });
  } catch (const std::exception& e) {
    line.finish();
    bench->disconnect();
    std::cerr << "wavebench run: " << e.what() << "\n";
    return 1;
  }
  line.finish();
  bench->disconnect();
  summarise_into_own_store(*store, outcome);

  try {
    std::cout << report::tables_as_text(
        report::session_tables({report::SessionRun{outcome.dir, {}}}));
  } catch (const std::exception& e) {
    std::cerr << "wavebench run: summary table: " << e.what() << "\n";
  }
  std::cout << "run " << outcome.run_id << ": " << storage::run_status_name(outcome.status);
  if (!outcome.reason.empty()) std::cout << " (" << outcome.reason << ")";
  if (outcome.results.contains("pass") && outcome.results["pass"].is_boolean()) {
    std::cout << (outcome.results["pass"].get<bool>() ? ", pass" : ", FAIL");
  }
  if (request.spec) {
    const auto& verdict = outcome.results["verdict"];
    std::cout << ", spec " << request.spec->name << ": "
              << (verdict.is_string() ? verdict.get<std::string>() : std::string("no verdict"));
  }
  std::cout << "\nresults: " << (outcome.dir / "results.json").string() << "\n";
  if (const auto w = outcome.results.find("warnings"); w != outcome.results.end()) {
    for (const auto& warning : *w)
      std::cerr << "wavebench run: warning: "
                << (warning.is_string() ? warning.get<std::string>() : warning.dump()) << "\n";
  }
  if (outcome.results.contains("report")) {
    std::cout << "report:  " << outcome.results["report"].get<std::string>() << "\n";
  } else if (outcome.results.contains("report_error")) {
    std::cout << "report:  not written (" << outcome.results["report_error"].get<std::string>()
              << ")\n";
  }
  return outcome.status == storage::RunStatus::kComplete ? 0 : 1;
}

}  // namespace

void register_run_commands(CLI::App& app, ExitStatus& status) {
  auto args = std::make_shared<RunArgs>();
  auto* cmd = app.add_subcommand(
      "run", "Run one bench procedure without a daemon (any procedure of the registry)");
  cmd->add_option("procedure", args->procedure, "a procedure of the registry (GET /api/procedures)")
      ->required()
      ->check(CLI::IsMember(procedures::procedure_names()));
  cmd->add_option("--bench", args->bench,
                  "'sim' (the in-process simulated bench) or a bench config file")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "run store: one folder per run and index.sqlite")
      ->capture_default_str();
  cmd->add_option("--positions", args->positions, "static: positions per output revolution");
  cmd->add_option("--loads", args->loads, "static: brake torques [N*m], e.g. 0,60")->delimiter(',');
  cmd->add_option("--window", args->window, "static: averaging window [s]");
  cmd->add_option("--repeats", args->repeats,
                  "any procedure: run it this many times; figures are the mean, the spread "
                  "between repeats is in their uncertainty");
  cmd->add_option("--rpm", args->rpm, "dynamic: input speed [rpm]");
  cmd->add_option("--revolutions", args->revolutions, "dynamic: output revolutions recorded");
  cmd->add_option("--load", args->load, "dynamic: brake torque [N*m]");
  cmd->add_option("--torques", args->torques, "lost-motion: brake torque ladder [N*m]")
      ->delimiter(',');
  cmd->add_option("--options", args->options_file,
                  "procedure options from YAML (see configs/procedures/); flags override it");
  cmd->add_option("--option", args->options, "any procedure option as KEY=VALUE (repeatable)");
  cmd->add_option("--limit", args->limits,
                  "pass/fail limit as KEY=VALUE, e.g. static_p2p_arcmin=6 (repeatable)");
  cmd->add_option("--spec", args->spec,
                  "product spec the run is accepted against (configs/specs/NAME.yaml): its "
                  "limits give the verdict, PASS, FAIL or UNDECIDED");
  cmd->add_option("--specs-dir", args->specs_dir,
                  "folder of product specs (default the shipped configs/specs)");
  cmd->add_flag("--no-twin", args->no_twin, "do not run the twin beside the bench");
  cmd->add_flag("--no-report", args->no_report, "do not write report.html");
  cmd->add_flag("--no-calibration", args->no_calibration, "do not calibrate the twin");
  cmd->add_flag("--quiet", args->quiet, "no progress line");
  cmd->callback([args, &status] {
    try {
      status.code = run_procedure(*args);
    } catch (const std::exception& e) {
      std::cerr << "wavebench run: " << e.what() << "\n";
      status.code = 1;
    }
  });
}

}  // namespace wavebench::cli
