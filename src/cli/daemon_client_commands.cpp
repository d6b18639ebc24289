// `wavebench status|start|abort|stop|reset|runs|export`: the CLI as the daemon's client. The
// work is in wavebench/daemon/client_commands.hpp; this file is the command line.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "wavebench/daemon/client_commands.hpp"
#include "wavebench/procedures/procedure_catalogue.hpp"

namespace wavebench::cli {
namespace {

struct DaemonClientOptions {
  std::string daemon_url;
  std::string token_file;
  double timeout_s = 45;

  daemon::ClientContext context() const {
    daemon::ClientContext ctx;
    ctx.daemon_url = daemon_url;
    ctx.token_file = token_file;
    ctx.timeout = std::chrono::milliseconds(static_cast<long long>(timeout_s * 1e3));
    ctx.connect_timeout = std::min(ctx.timeout, std::chrono::milliseconds(5000));
    ctx.out = &std::cout;
    ctx.err = &std::cerr;
    return ctx;
  }
};

std::string default_daemon_url() {
  if (const char* env = std::getenv("WAVEBENCH_DAEMON"); env && *env) return env;
  return "http://127.0.0.1:8470";
}

CLI::App* daemon_subcommand(CLI::App& app, const std::string& name, const std::string& help,
                            const std::shared_ptr<DaemonClientOptions>& options) {
  auto* sub = app.add_subcommand(name, help);
  sub->add_option("--daemon", options->daemon_url,
                  "the daemon's API (default $WAVEBENCH_DAEMON or http://127.0.0.1:8470)");
  sub->add_option("--token-file", options->token_file,
                  "the daemon's token (default $WAVEBENCH_TOKEN_FILE or "
                  "~/.config/wavebench/daemon.token)");
  sub->add_option("--timeout", options->timeout_s,
                  "seconds to wait for each answer of the daemon (connecting: at most 5)")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  return sub;
}

}  // namespace

void register_daemon_client_commands(CLI::App& app, ExitStatus& status) {
  auto options = std::make_shared<DaemonClientOptions>();
  options->daemon_url = default_daemon_url();

  daemon_subcommand(app, "status", "the daemon's state, bench, current run and fault", options)
      ->callback([options, &status] { status.code = daemon::client_status(options->context()); });

  struct StartArgs {
    std::string procedure;
    std::vector<std::string> options;
    std::string spec;
    bool wait = false;
  };
  auto start_args = std::make_shared<StartArgs>();
  auto* start = daemon_subcommand(app, "start", "start a run on the daemon's bench", options);
  start
      ->add_option("procedure", start_args->procedure,
                   "a procedure of the registry (GET /api/procedures)")
      ->required()
      ->check(CLI::IsMember(procedures::procedure_names()));
  start->add_option("--option", start_args->options,
                    "procedure option KEY=VALUE (repeatable; VALUE as JSON where it parses, e.g. "
                    "positions=4 loads_nm=[0,60])");
  start->add_option("--spec", start_args->spec,
                    "product spec the run is accepted against (its limits give the verdict)");
  start->add_flag("--wait", start_args->wait,
                  "follow the run's progress and exit 0 only when it completes");
  start->callback([options, start_args, &status] {
    status.code = daemon::client_start(options->context(), start_args->procedure,
                                       start_args->options, start_args->wait, start_args->spec);
  });

  daemon_subcommand(app, "abort", "abort the active run (the bench goes to its safe state)",
                    options)
      ->callback([options, &status] { status.code = daemon::client_abort(options->context()); });
  daemon_subcommand(app, "stop", "put the bench in its safe state (operator stop)", options)
      ->callback([options, &status] { status.code = daemon::client_stop(options->context()); });
  daemon_subcommand(app, "reset", "clear the bench's fault (or retry connecting it)", options)
      ->callback([options, &status] { status.code = daemon::client_reset(options->context()); });

  auto filter = std::make_shared<daemon::RunsFilter>();
  auto* runs = daemon_subcommand(app, "runs", "list the runs in the daemon's index", options);
  runs->add_option("--procedure", filter->procedure, "only this procedure");
  runs->add_option("--status", filter->status, "running, complete, aborted or incomplete");
  runs->add_option("--unit", filter->unit, "only this unit serial");
  runs->add_option("--spec", filter->spec, "only runs accepted against this product spec");
  runs->add_option("--verdict", filter->verdict,
                   "only runs with this verdict (as the API's verdict filter: pass, fail, none)");
  runs->add_option("--limit", filter->limit, "newest N runs (1 to 1000; default 50)");
  runs->callback([options, filter, &status] {
    status.code = daemon::client_runs(options->context(), *filter);
  });

  struct ExportArgs {
    std::string run_id, out, format = "csv", runs;
    bool partial = false;
  };
  auto export_args = std::make_shared<ExportArgs>();
  auto* exp = daemon_subcommand(app, "export", "copy a run's samples and results", options);
  exp->add_option("run_id", export_args->run_id, "run id (see 'wavebench runs')")->required();
  exp->add_option("--out", export_args->out,
                  "output folder (default ./RUN_ID): new, empty, or one an export wrote");
  // Checked by the command itself: a bad format is a message naming it and exit 2.
  exp->add_option("--format", export_args->format,
                  "samples as mat (MATLAB), hdf5, csv or json (default csv)");
  exp->add_option("--runs", export_args->runs,
                  "read the run from this run store folder instead of the daemon (no daemon "
                  "needed)");
  exp->add_flag("--partial", export_args->partial,
                "export a run that is still running: only the samples logged so far, every file "
                "marked partial (refused without it)");
  exp->callback([options, export_args, &status] {
    const auto& a = *export_args;
    status.code = a.runs.empty() ? daemon::client_export(options->context(), a.run_id, a.out,
                                                         a.format, a.partial)
                                 : daemon::local_export(options->context(), a.runs, a.run_id, a.out,
                                                        a.format, a.partial);
  });
}

}  // namespace wavebench::cli
