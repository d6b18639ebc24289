#pragma once
// The shared results store on PostgreSQL (libpq): one connection, opened on construction, the
// schema migrated to the newest version there (docs/formats/fleet-store.md). Not thread-safe:
// one store per thread (the outbox has its own, each CLI command its own).

#include <memory>
#include <string>

#include "wavebench/fleet/results_config.hpp"
#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet {

class PgConnection;

class PostgresResultsStore : public ResultsStore {
 public:
  // Connects (password from the config's password_file, else libpq's environment) and applies
  // the migrations the database lacks. Throws std::runtime_error with libpq's message.
  explicit PostgresResultsStore(const ResultsConfig& config);
  ~PostgresResultsStore() override;
  PostgresResultsStore(const PostgresResultsStore&) = delete;
  PostgresResultsStore& operator=(const PostgresResultsStore&) = delete;

  bool publish(const RunSummary& run) override;
  std::vector<FleetRunRow> runs(const FleetRunQuery& query) override;
  std::vector<TrendPoint> trend(const FigureQuery& query) override;
  SpcAnswer spc(const FigureQuery& query, const SpecLimits& limits) override;

  int schema_version();
  // Whether the connection still works (a failed call leaves it broken: make a new store).
  bool connected() const;

 private:
  std::unique_ptr<PgConnection> db_;
};

// The newest schema version this build writes.
int fleet_schema_version();

}  // namespace wavebench::fleet
