#pragma once
// A lone bench's own results store: the same summaries, queries and answers as the shared
// PostgreSQL store, in tables of the bench's run index (index.sqlite: fleet_runs,
// fleet_static_passes; docs/formats/fleet-store.md). The daemon fills them from the same
// RunSummary the outbox publishes, at the end of each run and, on start, for every finished
// run not yet there. One connection; not thread-safe: one store per thread.

#include <filesystem>
#include <set>
#include <string>

#include "wavebench/fleet/results_store.hpp"

struct sqlite3;

namespace wavebench::fleet {

class SqliteResultsStore : public ResultsStore {
 public:
  enum class Access {
    kReadWrite,  // creates the file and the tables, applies the migrations it lacks and adds
                 // the declared figure columns it lacks
    kReadOnly,   // queries only; refuses a file without the tables
  };
  // Throws std::runtime_error naming the file and SQLite's message.
  explicit SqliteResultsStore(const std::filesystem::path& file,
                              Access access = Access::kReadWrite);
  ~SqliteResultsStore() override;
  SqliteResultsStore(const SqliteResultsStore&) = delete;
  SqliteResultsStore& operator=(const SqliteResultsStore&) = delete;

  bool publish(const RunSummary& run) override;
  std::vector<FleetRunRow> runs(const FleetRunQuery& query) override;
  std::vector<TrendPoint> trend(const FigureQuery& query) override;
  SpcAnswer spc(const FigureQuery& query, const SpecLimits& limits) override;

  int schema_version();

 private:
  sqlite3* db_ = nullptr;
  // Declared figure columns an older file opened read-only lacks: they read as NULL.
  std::set<std::string> absent_;
};

// The newest schema version of the SQLite store this build writes.
int sqlite_fleet_schema_version();

}  // namespace wavebench::fleet
