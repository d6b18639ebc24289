#pragma once
// The bench records every run locally first (run folder, index.sqlite); the outbox then sends
// each finished run to the shared results store from its own thread, when the store can be
// reached. What was sent is a table of the bench's index (fleet_published); what is to send is
// every finished run not in it, so a run finished while the server was away, or while the
// daemon was down, goes when both are back. The store's insert is idempotent by (bench, run
// id): a send repeated after a lost answer changes nothing. Never on the bench thread: enqueue()
// only queues.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "wavebench/fleet/results_store.hpp"
#include "wavebench/fleet/run_summary.hpp"
#include "wavebench/storage/run_store.hpp"

struct sqlite3;

namespace wavebench::fleet {

using StoreFactory = std::function<std::unique_ptr<ResultsStore>()>;

struct OutboxOptions {
  BenchIdentity identity;
  std::chrono::milliseconds retry_first{500};
  std::chrono::milliseconds retry_max{60000};
  // Each failure and recovery, for the daemon's log (on the outbox's thread).
  std::function<void(const std::string&)> on_event;
  // The index's table of the runs sent, one per kind of store: a bench switched from its own
  // store to a shared one sends the shared one every run.
  std::string ledger = "fleet_published";
};

struct OutboxCounts {
  std::size_t pending = 0;
  std::size_t sent = 0;           // by this outbox (inserted or found already there)
  std::size_t failures = 0;       // attempts that could not reach or write the store
  std::string last_error;         // of the newest failure; kept after a recovery
  std::string last_published_at;  // ISO 8601 UTC of the newest run sent; empty: none yet
  // When the next attempt after a failure is due; none while not waiting on a retry.
  std::optional<std::chrono::steady_clock::time_point> next_attempt;
};

class Outbox {
 public:
  // Opens `store`'s index (its own connection) and queues every finished run not yet published.
  // `connect` makes a store connection; it is called on the outbox's thread, again after a
  // failure. Throws std::runtime_error when the index cannot be opened.
  Outbox(const storage::RunStore& store, StoreFactory connect, OutboxOptions options);
  ~Outbox();
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  void start();
  // Sends `run_id` when it can (after it finished). Thread-safe, never blocks on the store.
  void enqueue(const std::string& run_id);
  // Stops the thread; what was not sent stays pending in the index for the next start.
  void stop();
  OutboxCounts counts() const;
  // Waits until nothing is pending or `timeout` passes; whether nothing is pending (tests).
  bool wait_idle(std::chrono::milliseconds timeout) const;

 private:
  void run();
  bool send_one(ResultsStore& store, const std::string& run_id);
  void mark_published(const std::string& run_id);

  const storage::RunStore& store_;
  StoreFactory connect_;
  OutboxOptions options_;
  sqlite3* index_ = nullptr;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::deque<std::string> pending_;
  OutboxCounts counts_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace wavebench::fleet
