// wavebenchd: the bench daemon (issue #5). Owns the bench, runs procedures on request, keeps
// every run on disk, and serves the local HTTP + JSON API the `wavebench` CLI talks to.
//
// Exit status: 0 after SIGTERM/SIGINT (the bench left in its safe state, an active run
// finished aborted), 1 on a runtime failure, 2 on a bad command line or config.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <chrono>
#include <csignal>
#include <exception>
#include <iostream>

#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/daemon/accounts.hpp"
#include "wavebench/daemon/api_token.hpp"
#include "wavebench/daemon/async_logging.hpp"
#include "wavebench/daemon/console_files.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/daemon/daemon_logging.hpp"
#include "wavebench/daemon/daemon_options.hpp"
#include "wavebench/daemon/last_resort_guard.hpp"
#include "wavebench/fleet/results_config.hpp"
#include "wavebench/procedures/allocator_policy.hpp"
#include "wavebench/procedures/software_version.hpp"

namespace {

using namespace wavebench;

int fail(int code, const std::string& message) {
  std::cerr << "wavebenchd: " << message << "\n";
  return code;
}

int run(const daemon::DaemonOptions& options) {
  // The config first: a bad one must stop us before anything is created.
  bench::BenchConfig config;
  try {
    config = bench::bench_config_from_argument(options.config);
  } catch (const std::exception& e) {
    return fail(2, std::string("--config ") + options.config + ": " + e.what());
  }
  daemon::LoginSetup setup_logins;
  fleet::ResultsConfig results;
  if (!options.results_config.empty()) {
    try {
      results = fleet::load_results_config(options.results_config);
      // A missing or readable-by-all password file is a config error, found before the first run.
      if (results.shared() && !results.password_file.empty()) {
        (void)fleet::read_password_file(results.password_file);
      }
    } catch (const std::exception& e) {
      return fail(2, std::string("--results ") + options.results_config.string() + ": " + e.what());
    }
  }
  // Operators by name: a bad accounts file is a config error, like a bad bench config.
  if (!options.accounts_file.empty()) {
    try {
      setup_logins.accounts = daemon::load_accounts(options.accounts_file);
    } catch (const daemon::AccountsFileRefused& e) {
      return fail(2, std::string("--accounts: ") + e.what());
    }
  }
  setup_logins.idle_timeout = std::chrono::seconds(options.session_idle_timeout_s);
  setup_logins.max_age = std::chrono::seconds(options.session_max_age_s);
  const auto token_file =
      options.token_file.empty() ? daemon::default_token_file() : options.token_file;
  daemon::DaemonSetup setup;
  try {
    setup.token = daemon::load_or_create_token(token_file);
  } catch (const daemon::TokenFileRefused& e) {
    return fail(2, e.what());
  } catch (const std::exception& e) {
    return fail(1, e.what());
  }
  // Logging creates the runs folder's logs/: only once every input was accepted.
  try {
    daemon::setup_daemon_logging(
        options.log_dir.empty() ? options.runs_dir / "logs" : options.log_dir, options.verbose);
  } catch (const std::exception& e) {
    return fail(2, e.what());
  }
  if (!daemon::is_loopback(options.listen)) {
    spdlog::warn(
        "listening on {} (--allow-remote): the API, and the bench with it, can be "
        "reached from the network; the token is all that guards it",
        options.listen.host);
  }
  setup.allowed_hosts = options.allowed_hosts;
  if (!setup_logins.accounts.empty())
    spdlog::info("{} operator accounts from {}", setup_logins.accounts.size(),
                 options.accounts_file.string());
  setup.logins = std::move(setup_logins);
  spdlog::info("wavebenchd {} ({}) starting: bench config {}, runs in {}, token in {}",
               procedures::software_version(), procedures::software_commit(), config.source,
               options.runs_dir.string(), token_file.string());
  setup.bench_factory = [config] { return bench::make_bench(config); };
  setup.launcher = daemon::make_executor_run_launcher();
  setup.bench_check = daemon::make_commissioning_check();
  setup.runs_dir = options.runs_dir;
  setup.results = results;
  setup.specs_dir = options.specs_dir;
  setup.listen_address = options.listen.host;
  setup.port = options.listen.port;
  setup.config_text = config.text;
  setup.software_version = procedures::software_version();
  setup.software_commit = procedures::software_commit();
  setup.console_root = options.web_root.empty() ? daemon::default_console_root() : options.web_root;
  if (setup.console_root.empty()) {
    spdlog::warn("no console files found (--web-root): the API is served, the console is not");
  } else {
    spdlog::info("console from {}", setup.console_root.string());
  }

  boost::asio::io_context signals_io;
  boost::asio::signal_set signals(signals_io, SIGINT, SIGTERM);
  std::string stop_reason;
  signals.async_wait([&](const boost::system::error_code& ec, int number) {
    if (!ec)
      stop_reason = std::string("daemon stopped by ") + (number == SIGINT ? "SIGINT" : "SIGTERM");
  });

  std::unique_ptr<daemon::Daemon> d;
  try {
    d = std::make_unique<daemon::Daemon>(std::move(setup));
  } catch (const std::exception& e) {
    return fail(1, std::string("--runs ") + options.runs_dir.string() + ": " + e.what());
  }
  daemon::install_last_resort_guard([&d](const std::string& what) {
    spdlog::critical("{}: bench to its safe state, active run marked, then abort", what);
    d->emergency_stop("daemon failure: " + what);
    daemon::finish_async_logging();
  });
  try {
    d->start();
  } catch (const config::ConfigError& e) {
    return fail(2, std::string("--config ") + options.config + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    return fail(2, std::string("--config ") + options.config + ": " + e.what());
  } catch (const std::exception& e) {
    return fail(1, e.what());
  }
  // Tests and scripts wait for this line to know the port.
  std::cout << "wavebenchd: listening on http://" << options.listen.host << ":" << d->port()
            << std::endl;
  signals_io.run();
  spdlog::info("{}: safe state, ending the run if one is active", stop_reason);
  d->shutdown(stop_reason);
  daemon::remove_last_resort_guard();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  procedures::use_allocator_policy();
  CLI::App app{"wavebenchd - the strain-wave gear test bench daemon"};
  app.set_version_flag("--version", std::string("wavebenchd ") + procedures::software_version() +
                                        " (commit " + procedures::software_commit() + ")");
  daemon::DaemonOptions options;
  std::string listen = "127.0.0.1:8470";
  std::string runs_dir = options.runs_dir.string();
  std::string token_file;
  std::string log_dir;
  std::string specs_dir;
  std::string results_config;
  app.add_option("--config", options.config,
                 "bench config (YAML), or 'sim' for the in-process simulated bench")
      ->required();
  app.add_option("--runs", runs_dir, "runs folder (run folders and the SQLite index)")
      ->capture_default_str();
  app.add_option("--listen", listen, "HOST:PORT of the API (port 0: any free port)")
      ->capture_default_str();
  app.add_option("--token-file", token_file,
                 "token for requests that move hardware (created 0600 if missing; default "
                 "$WAVEBENCH_TOKEN_FILE or ~/.config/wavebench/daemon.token)");
  app.add_option("--log-dir", log_dir, "rotating log folder (default RUNS/logs)");
  std::string web_root;
  app.add_option("--web-root", web_root,
                 "the console's files (default $WAVEBENCH_WEB_DIR, the installed ones, or the "
                 "build tree's web/)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--specs-dir", specs_dir,
                 "product specs a run may name, one NAME.yaml each (default the shipped "
                 "specs of the shipped configs)");
  app.add_option("--results", results_config,
                 "where runs go besides the runs folder: a YAML file with `results: {store: "
                 "postgresql, url, password_file, bench, station}` (a lab's shared store)");
  std::string accounts_file;
  app.add_option("--accounts", accounts_file,
                 "operators by name: a YAML file of {name, password_hash, role} (`wavebench "
                 "account add`); without it only the token logs in");
  app.add_option("--session-idle-timeout", options.session_idle_timeout_s,
                 "seconds a console session lives unused")
      ->check(CLI::Range(1LL, 7LL * 24 * 3600))
      ->capture_default_str();
  app.add_option("--session-max-age", options.session_max_age_s,
                 "seconds a console session lives at most, used or not")
      ->check(CLI::Range(1LL, 30LL * 24 * 3600))
      ->capture_default_str();
  app.add_flag("--verbose", options.verbose, "debug logging");
  app.add_flag("--allow-remote", options.allow_remote,
               "allow --listen on an address other machines can reach (logged as a warning)");
  app.add_option("--allow-host", options.allowed_hosts,
                 "a host name browsers may use to reach the API (repeatable; IP addresses and "
                 "localhost always work)")
      ->check([](const std::string& name) {
        const bool ok = !name.empty() && name.size() <= 253 &&
                        name.find_first_not_of(
                            "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUV"
                            "WXYZ0123456789-.") == std::string::npos;
        return ok ? std::string() : "got '" + name + "', expected a DNS name";
      });
  try {
    app.parse(argc, argv);
    options.listen = daemon::parse_listen_address(listen);
    if (!daemon::is_loopback(options.listen) && !options.allow_remote) {
      return fail(2, "--listen: got '" + listen +
                         "', expected a loopback address (127.0.0.1, ::1); to serve the "
                         "network add --allow-remote");
    }
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const std::invalid_argument& e) {
    return fail(2, e.what());
  }
  options.runs_dir = runs_dir;
  options.token_file = token_file;
  options.log_dir = log_dir;
  options.web_root = web_root;
  options.specs_dir = specs_dir;
  options.results_config = results_config;
  options.accounts_file = accounts_file;
  int rc = 1;
  try {
    rc = run(options);
  } catch (const std::exception& e) {
    rc = fail(1, e.what());
  }
  daemon::finish_async_logging();  // every queued line written, whichever way run() ended
  return rc;
}
