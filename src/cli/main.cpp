// wavebench: the command-line tool of the strain-wave gear test bench.
#include <exception>
#include <iostream>

#include "account_commands.hpp"
#include "commands.hpp"
#include "wavebench/procedures/allocator_policy.hpp"
#include "wavebench/procedures/software_version.hpp"

int main(int argc, char** argv) {
  wavebench::procedures::use_allocator_policy();
  CLI::App app{"wavebench - strain-wave gear test bench and digital twin"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("wavebench ") +
                                        wavebench::procedures::software_version() + " (commit " +
                                        wavebench::procedures::software_commit() + ")");
  wavebench::cli::ExitStatus status;
  wavebench::cli::register_sim_commands(app, status);
  wavebench::cli::register_can_commands(app, status);
  wavebench::cli::register_brake_commands(app, status);
  wavebench::cli::register_simbench_commands(app, status);
  wavebench::cli::register_run_commands(app, status);
  wavebench::cli::register_daemon_client_commands(app, status);
  wavebench::cli::register_report_commands(app, status);
  wavebench::cli::register_bench_commands(app, status);
  wavebench::cli::register_fleet_commands(app, status);
  wavebench::cli::register_account_commands(app, status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::cerr << "wavebench: " << e.what() << "\n";
    return 1;
  }
  return status.code;
}
