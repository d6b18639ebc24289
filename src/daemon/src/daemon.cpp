#include "wavebench/daemon/daemon.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "wavebench/daemon/console_files.hpp"
#include "wavebench/daemon/fleet_api.hpp"
#include "wavebench/daemon/publishing_run_launcher.hpp"
#include "wavebench/exports/export_scratch.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"

namespace wavebench::daemon {

namespace {

DaemonSetup checked(DaemonSetup setup) {
  if (!setup.bench_factory) throw std::invalid_argument("daemon: no bench factory");
  if (!setup.launcher) throw std::invalid_argument("daemon: no run launcher");
  if (setup.token.empty()) throw std::invalid_argument("daemon: empty token");
  if (setup.api_threads < 1) setup.api_threads = 1;
  return setup;
}

// Every finished run goes to the results store: the shared one when configured, else the
// bench's own summaries in its index (what /api/fleet answers from).
std::unique_ptr<fleet::Outbox> make_outbox(DaemonSetup& setup, const storage::RunStore& store) {
  fleet::StoreFactory connect = setup.results_store;
  if (!connect && setup.results.shared()) {
    connect = [config = setup.results]() -> std::unique_ptr<fleet::ResultsStore> {
      return std::make_unique<fleet::PostgresResultsStore>(config);
    };
  } else if (!connect) {
    connect = [index = store.root() / "index.sqlite"]() -> std::unique_ptr<fleet::ResultsStore> {
      return std::make_unique<fleet::SqliteResultsStore>(index);
    };
  }
  fleet::OutboxOptions options;
  if (!setup.results.shared()) options.ledger = "fleet_own_published";
  options.identity = {setup.results.bench, setup.results.station};
  options.retry_max = std::chrono::milliseconds(static_cast<long>(setup.results.retry_max_s * 1e3));
  options.retry_first = std::min(options.retry_first, options.retry_max);
  options.on_event = [](const std::string& text) { spdlog::warn("{}", text); };
  return std::make_unique<fleet::Outbox>(store, std::move(connect), std::move(options));
}

std::unique_ptr<RunLauncher> publishing(std::unique_ptr<RunLauncher> launcher,
                                        fleet::Outbox* outbox) {
  if (!outbox) return launcher;
  return std::make_unique<PublishingRunLauncher>(std::move(launcher), *outbox);
}

}  // namespace

Daemon::Daemon(DaemonSetup setup)
    : setup_(checked(std::move(setup))),
      store_(setup_.runs_dir, setup_.software_version),
      outbox_(make_outbox(setup_, store_)),
      launcher_(publishing(std::move(setup_.launcher), outbox_.get())),
      live_(setup_.live_capacity),
      bench_thread_(setup_.bench_factory, store_, *launcher_, setup_.config_text, live_),
      api_(bench_thread_, store_, live_, setup_.token, HostCheck(setup_.allowed_hosts),
           setup_.specs_dir, std::make_shared<const ConsoleFiles>(setup_.console_root),
           SoftwareIdentity{setup_.software_version, setup_.software_commit}) {
  bench_thread_.set_check(setup_.bench_check);
  api_.set_logins(setup_.logins);
  api_.set_fleet_queries(make_fleet_queries(setup_.results, store_.root() / "index.sqlite"));
  api_.set_results_status([this] { return results_status_json(); });
  storage::RunQuery incomplete;
  incomplete.status = storage::RunStatus::kIncomplete;
  spdlog::info("runs in {}: {} indexed, {} incomplete", store_.root().string(), store_.count_runs(),
               store_.count_runs(incomplete));
  // Scratch of downloads a killed daemon was answering (issue #22): nothing else removes it.
  if (const auto stale = exports::remove_stale_export_scratch(); stale > 0) {
    spdlog::info("removed {} stale export scratch folder(s) of an earlier daemon", stale);
  }
  spdlog::info("results store: {} ({} runs to send)",
               setup_.results.shared() ? setup_.results.url : "this bench's own (index.sqlite)",
               outbox_->counts().pending);
}

Daemon::~Daemon() {
  shutdown("daemon shutting down");
}

void Daemon::start() {
  if (outbox_) outbox_->start();
  bench_thread_.start();
  server_ = std::make_unique<HttpServer>(
      io_, setup_.listen_address, setup_.port,
      [this](const ApiRequest& request) { return api_.handle(request); });
  server_->start();
  for (int i = 0; i < setup_.api_threads; ++i) {
    api_threads_.emplace_back([this] { serve_api(); });
  }
  spdlog::info("listening on http://{}:{}", setup_.listen_address, server_->port());
}

void Daemon::serve_api() noexcept {
  // Handlers answer errors themselves; anything that still escapes is a bug, and must not end
  // the process with the bench moving: the bench goes safe, and the thread goes on serving.
  for (;;) {
    try {
      io_.run();
      return;
    } catch (const std::exception& e) {
      spdlog::critical("API thread: {}; bench to its safe state", e.what());
      bench_thread_.stop(std::string("internal error in the API: ") + e.what());
    } catch (...) {
      spdlog::critical("API thread: unknown exception; bench to its safe state");
      bench_thread_.stop("internal error in the API");
    }
  }
}

void Daemon::emergency_stop(const std::string& reason) noexcept {
  try {
    bench_thread_.emergency_stop(reason, std::chrono::seconds(5));
  } catch (...) {
  }
}

nlohmann::json Daemon::results_status_json() const {
  const auto c = outbox_->counts();
  const auto text = [](const std::string& t) {
    return t.empty() ? nlohmann::json(nullptr) : nlohmann::json(t);
  };
  nlohmann::json next = nullptr;
  if (c.next_attempt) {
    const auto wait =
        std::chrono::duration<double>(*c.next_attempt - std::chrono::steady_clock::now());
    next = std::max(0.0, wait.count());
  }
  // libpq's messages name the host, user and database, never the password (refused in the
  // URL, read from a file).
  return {{"kind", setup_.results.shared() ? "postgresql" : "sqlite"},
          {"pending", c.pending},
          {"sent", c.sent},
          {"failures", c.failures},
          {"last_error", text(c.last_error)},
          {"last_published_at", text(c.last_published_at)},
          {"next_attempt_in_s", next}};
}

unsigned short Daemon::port() const {
  return server_ ? server_->port() : 0;
}

void Daemon::shutdown(const std::string& reason) {
  if (shut_down_) return;
  shut_down_ = true;
  // The bench first: a start request waiting on the bench thread gets its answer, and the run
  // ends aborted with its data on disk before the API goes away.
  bench_thread_.shutdown(reason);
  if (server_) server_->stop();
  io_.stop();
  for (auto& t : api_threads_) t.join();
  api_threads_.clear();
  server_.reset();
  // What was not sent stays pending in the index: the next start sends it.
  if (outbox_) outbox_->stop();
  spdlog::info("stopped ({})", reason);
}

}  // namespace wavebench::daemon
