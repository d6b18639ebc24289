// wavebench bench check CONFIG: the commissioning check (devices left inactive). A drive that
// does not state its velocity unit (no 0x60A9) has its units compared with the encoders by a
// short, slow, bounded motion (issue #20): a unit mismatch is found before a run could turn
// the input 60x too fast. --no-motion keeps everything still (that row then says so).
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "wavebench/bench/bench_check.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/config/config_error.hpp"

namespace wavebench::cli {
namespace {

struct CheckArgs {
  std::string config = "simulated";
  bool json = false;
  bool motion = true;
};

int run_check(const CheckArgs& a) {
  bench::BenchConfig config;
  try {
    config = bench::bench_config_from_argument(a.config);
  } catch (const config::ConfigError& e) {
    std::cerr << "wavebench bench check: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "wavebench bench check: " << e.what() << "\n";
    return 2;
  }
  // The table (or the JSON) is the output, alone on stdout: connect's warnings go to stderr,
  // and its progress lines are not shown.
  spdlog::set_default_logger(spdlog::stderr_color_mt("wavebench-bench-check"));
  spdlog::set_level(spdlog::level::warn);
  std::unique_ptr<bench::Bench> bench;
  try {
    bench = bench::make_bench(config);
  } catch (const std::exception& e) {
    std::cerr << "wavebench bench check: bench '" << config.description.name
              << "' cannot be built: " << e.what() << "\n";
    return 1;
  }
  auto* canopen = bench::canopen_bench_of(*bench);
  if (!canopen) {
    std::cerr << "wavebench bench check: bench '" << config.description.name
              << "' is not a CANopen bench\n";
    return 1;
  }
  bench::CheckOptions options;
  options.motion = a.motion;
  const auto report = bench::check_bench(*canopen, options);
  bench->disconnect();
  if (a.json) {
    std::cout << bench::check_report_json(report).dump(2) << "\n";
  } else {
    std::cout << bench::format_check_table(report);
  }
  return report.all_green() ? 0 : 1;
}

}  // namespace

void register_bench_commands(CLI::App& app, ExitStatus& status) {
  auto* bench = app.add_subcommand("bench", "Bench commissioning");
  bench->require_subcommand(1);
  auto args = std::make_shared<CheckArgs>();
  auto* check = bench->add_subcommand(
      "check",
      "Commissioning check: nodes, identity, device type, used objects (EDS), PDO mapping, "
      "heartbeats or node guarding, SYNC round trip, bus load, brake registers, drive units "
      "(0x60A8/0x60A9, else a short bounded motion unless --no-motion); exit 0 all green, 1 any "
      "red, 2 bad config");
  check->add_option("config", args->config, "'sim' or a bench config file")->capture_default_str();
  check->add_flag("--json", args->json, "rows as JSON instead of a table");
  check->add_flag("--motion,!--no-motion", args->motion,
                  "(default) where the drive does not state its velocity unit (no 0x60A9), turn "
                  "the input ~0.1 rev at 10 rpm (bounded by the encoders: stopped beyond 30 rpm "
                  "or 0.2 rev) to compare the drive's units with the encoders; the drive is off "
                  "again after. --no-motion: nothing moves");
  check->callback([args, &status] {
    try {
      status.code = run_check(*args);
    } catch (const std::exception& e) {
      std::cerr << "wavebench bench check: " << e.what() << "\n";
      status.code = 1;
    }
  });
}

}  // namespace wavebench::cli
