#pragma once
// Each area of the CLI adds its subcommands to the app. A subcommand's callback stores its
// exit status in `status` (0 ok, 1 runtime failure, 2 bad input or config).

#include <CLI/CLI.hpp>

namespace wavebench::cli {

struct ExitStatus {
  int code = 0;
};

void register_sim_commands(CLI::App& app, ExitStatus& status);       // sim (twin)
void register_can_commands(CLI::App& app, ExitStatus& status);       // can scan|nmt|sdo-*|dump
void register_brake_commands(CLI::App& app, ExitStatus& status);     // brake, sim-brake
void register_simbench_commands(CLI::App& app, ExitStatus& status);  // simbench
void register_run_commands(CLI::App& app, ExitStatus& status);       // run PROCEDURE
void register_daemon_client_commands(CLI::App& app,
                                     ExitStatus& status);          // status|start|abort|runs|export
void register_report_commands(CLI::App& app, ExitStatus& status);  // report RUN_DIR
void register_bench_commands(CLI::App& app, ExitStatus& status);   // bench check
void register_fleet_commands(CLI::App& app, ExitStatus& status);   // fleet runs|trend|spc

}  // namespace wavebench::cli
