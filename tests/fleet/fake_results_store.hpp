#pragma once
// An in-memory shared store for the outbox's own tests: counts every publish per (bench, run
// id), and fails while told to (the server away).

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet::testing {

struct FakeServer {
  std::mutex mutex;
  std::map<std::string, int> inserted;  // "bench/run id" -> rows (must stay 1)
  std::map<std::string, RunSummary> rows;
  int publish_calls = 0;
  std::atomic<bool> down{false};
};

class FakeResultsStore : public ResultsStore {
 public:
  explicit FakeResultsStore(std::shared_ptr<FakeServer> server) : server_(std::move(server)) {
    if (server_->down) throw std::runtime_error("fake store: connection refused");
  }
  bool publish(const RunSummary& run) override {
    if (server_->down) throw std::runtime_error("fake store: server closed the connection");
    std::lock_guard lock(server_->mutex);
    ++server_->publish_calls;
    const auto key = run.bench + "/" + run.run_id;
    if (server_->rows.count(key)) return false;  // ON CONFLICT DO NOTHING
    server_->rows[key] = run;
    ++server_->inserted[key];
    return true;
  }
  std::vector<FleetRunRow> runs(const FleetRunQuery&) override { return {}; }
  std::vector<TrendPoint> trend(const FigureQuery&) override { return {}; }
  SpcAnswer spc(const FigureQuery&, const SpecLimits&) override { return {}; }

 private:
  std::shared_ptr<FakeServer> server_;
};

inline StoreFactory fake_factory(std::shared_ptr<FakeServer> server) {
  return [server]() -> std::unique_ptr<ResultsStore> {
    return std::make_unique<FakeResultsStore>(server);
  };
}

}  // namespace wavebench::fleet::testing
