#include "wavebench/fleet/outbox.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace wavebench::fleet {

namespace {

void exec(sqlite3* db, const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw std::runtime_error("outbox: " + text);
  }
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  return std::string(buf, std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm));
}

nlohmann::json read_results(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return nullptr;  // a run that ended before it wrote results: the row alone
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str(), nullptr, false);  // unreadable: discarded, row alone
}

}  // namespace

Outbox::Outbox(const storage::RunStore& store, StoreFactory connect, OutboxOptions options)
    : store_(store), connect_(std::move(connect)), options_(std::move(options)) {
  const auto path = store_.root() / "index.sqlite";
  if (sqlite3_open_v2(path.c_str(), &index_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK) {
    std::string message = index_ ? sqlite3_errmsg(index_) : "out of memory";
    sqlite3_close(index_);
    index_ = nullptr;
    throw std::runtime_error("outbox: cannot open " + path.string() + ": " + message);
  }
  sqlite3_busy_timeout(index_, 5000);
  try {
    if (options_.ledger.empty() ||
        options_.ledger.find_first_not_of("abcdefghijklmnopqrstuvwxyz_") != std::string::npos) {
      throw std::invalid_argument("outbox: ledger '" + options_.ledger +
                                  "', expected a table name of [a-z_]");
    }
    exec(index_, ("CREATE TABLE IF NOT EXISTS " + options_.ledger +
                  " (run_id TEXT PRIMARY KEY, published_at TEXT NOT NULL)")
                     .c_str());
    sqlite3_stmt* s = nullptr;
    const std::string unsent =
        "SELECT id FROM runs WHERE status <> 'running' AND id NOT IN "
        "(SELECT run_id FROM " +
        options_.ledger + ") ORDER BY id";
    if (sqlite3_prepare_v2(index_, unsent.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      throw std::runtime_error(std::string("outbox: ") + sqlite3_errmsg(index_));
    }
    while (sqlite3_step(s) == SQLITE_ROW) {
      pending_.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)));
    }
    sqlite3_finalize(s);
  } catch (...) {
    sqlite3_close(index_);
    throw;
  }
}

Outbox::~Outbox() {
  stop();
  sqlite3_close(index_);
}

void Outbox::start() {
  if (thread_.joinable()) return;
  thread_ = std::thread([this] { run(); });
}

void Outbox::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Outbox::enqueue(const std::string& run_id) {
  if (run_id.empty()) return;
  {
    std::lock_guard lock(mutex_);
    if (std::find(pending_.begin(), pending_.end(), run_id) != pending_.end()) return;
    pending_.push_back(run_id);
  }
  changed_.notify_all();
}

OutboxCounts Outbox::counts() const {
  std::lock_guard lock(mutex_);
  OutboxCounts c = counts_;
  c.pending = pending_.size();
  return c;
}

bool Outbox::wait_idle(std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  return changed_.wait_for(lock, timeout, [&] { return pending_.empty(); });
}

void Outbox::mark_published(const std::string& run_id) {
  sqlite3_stmt* s = nullptr;
  const std::string insert =
      "INSERT OR IGNORE INTO " + options_.ledger + " (run_id, published_at) VALUES (?1, ?2)";
  if (sqlite3_prepare_v2(index_, insert.c_str(), -1, &s, nullptr) != SQLITE_OK) {
    throw std::runtime_error(std::string("outbox: ") + sqlite3_errmsg(index_));
  }
  const std::string at = now_utc();
  sqlite3_bind_text(s, 1, run_id.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s, 2, at.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(s);
  sqlite3_finalize(s);
  if (rc != SQLITE_DONE) {
    throw std::runtime_error(std::string("outbox: ") + sqlite3_errmsg(index_));
  }
}

// Whether the run was published (not: not indexed here, or still running).
bool Outbox::send_one(ResultsStore& db, const std::string& run_id) {
  const auto run = store_.find_run(run_id);
  if (!run) return false;  // not indexed here: nothing to send
  if (run->status == storage::RunStatus::kRunning) return false;  // enqueued again at its end
  const auto summary =
      summarise_run(*run, read_results(store_.paths(run_id).results), options_.identity);
  db.publish(summary);
  mark_published(run_id);
  return true;
}

void Outbox::run() {
  std::unique_ptr<ResultsStore> db;
  auto delay = options_.retry_first;
  bool failing = false;
  const auto event = [&](const std::string& text) {
    if (options_.on_event) options_.on_event(text);
  };
  for (;;) {
    std::string id;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || !pending_.empty(); });
      if (stopping_) return;
      id = pending_.front();
    }
    try {
      if (!db) db = connect_();
      const bool sent = send_one(*db, id);
      {
        std::lock_guard lock(mutex_);
        const auto it = std::find(pending_.begin(), pending_.end(), id);
        if (it != pending_.end()) pending_.erase(it);
        if (sent) {
          ++counts_.sent;
          counts_.last_published_at = now_utc();
        }
        counts_.next_attempt.reset();
      }
      changed_.notify_all();
      if (failing) event("results store: reachable again, sending the runs that waited");
      failing = false;
      delay = options_.retry_first;
    } catch (const std::exception& e) {
      // Reconnect on the next attempt; a run the store refuses goes behind the others so that
      // it holds none of them up.
      db.reset();
      {
        std::lock_guard lock(mutex_);
        ++counts_.failures;
        counts_.last_error = e.what();
        const auto it = std::find(pending_.begin(), pending_.end(), id);
        if (it != pending_.end()) {
          pending_.erase(it);
          pending_.push_back(id);
        }
        counts_.next_attempt = std::chrono::steady_clock::now() + delay;
      }
      event("results store: run " + id + " not sent (" + e.what() + "); retrying in " +
            std::to_string(delay.count()) + " ms");
      failing = true;
      std::unique_lock lock(mutex_);
      if (changed_.wait_for(lock, delay, [&] { return stopping_; })) return;
      delay = std::min(delay * 2, options_.retry_max);
    }
  }
}

}  // namespace wavebench::fleet
