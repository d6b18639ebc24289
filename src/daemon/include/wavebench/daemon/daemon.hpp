#pragma once
// wavebenchd as an object: the run store (recovered at start), the bench thread, the API and
// its HTTP server on its own threads. main() adds the config, the token file, logging and
// signals; tests run it in-process on an ephemeral port.

#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_server.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/run_launcher.hpp"
#include "wavebench/fleet/outbox.hpp"
#include "wavebench/fleet/results_config.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

inline constexpr unsigned short kDefaultPort = 8470;

struct DaemonSetup {
  BenchFactory bench_factory;
  std::unique_ptr<RunLauncher> launcher;
  BenchCheck bench_check;  // GET /api/bench/check; none: 503
  std::filesystem::path runs_dir;
  std::filesystem::path specs_dir;  // product specs a run may name; empty: the shipped ones
  std::string listen_address = "127.0.0.1";
  unsigned short port = kDefaultPort;  // 0 = ephemeral
  std::string token;
  std::string config_text;  // the bench config, copied into every run
  std::string software_version = WAVEBENCH_SOFTWARE_VERSION;
  std::string software_commit = "unknown";
  // A start request waits for its run id and DaemonApi::kMaxConcurrentReads costly reads may
  // run; the rest keep status, abort and stop answered.
  int api_threads = 6;
  std::vector<std::string> allowed_hosts;  // Host names beside IP literals and localhost
  std::size_t live_capacity = 8192;
  std::filesystem::path console_root;  // the console's files; empty: no console
  // `--results FILE`: with a shared store, every finished run also goes there (the outbox);
  // sqlite or none: to the bench's own summaries in index.sqlite.
  fleet::ResultsConfig results;
  // Makes the store's connection (on the outbox's thread); empty: PostgreSQL from `results`,
  // or the bench's own SQLite store. Tests put a stand-in here.
  fleet::StoreFactory results_store;
  // `--accounts FILE` and the session timeouts (daemon_api.hpp).
  LoginSetup logins;
};

class Daemon {
 public:
  // Opens the run store, which marks runs left running by a killed daemon as incomplete.
  explicit Daemon(DaemonSetup setup);
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  // Builds and connects the bench, then listens. Throws what the bench factory threw (a bad
  // config) or std::runtime_error when it cannot listen.
  void start();
  unsigned short port() const;
  // Safe state, the active run finished aborted with `reason`, bench disconnected, server
  // stopped. Idempotent.
  void shutdown(const std::string& reason);
  // The last resort before the process ends abnormally (std::terminate): trips the bench and
  // waits a bounded time for the active run to be marked. Callable from any thread.
  void emergency_stop(const std::string& reason) noexcept;

  storage::RunStore& store() { return store_; }
  // The results store's outbox: to the shared store, else to the bench's own.
  fleet::Outbox* outbox() { return outbox_.get(); }
  // GET /api/status's `results_store`: kind, pending, last error, when the next attempt is.
  nlohmann::json results_status_json() const;
  BenchThread& bench_thread() { return bench_thread_; }
  const DaemonApi& api() const { return api_; }

 private:
  DaemonSetup setup_;
  storage::RunStore store_;
  std::unique_ptr<fleet::Outbox> outbox_;
  std::unique_ptr<RunLauncher> launcher_;  // setup_'s, wrapped to publish when outbox_ is set
  LiveSampleBuffer live_;
  BenchThread bench_thread_;
  DaemonApi api_;
  boost::asio::io_context io_;
  std::unique_ptr<HttpServer> server_;
  std::vector<std::thread> api_threads_;
  void serve_api() noexcept;

  bool shut_down_ = false;
};

}  // namespace wavebench::daemon
