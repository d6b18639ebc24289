// The run history under a big index (issue #10 item 7; target: a page of 10,000 runs in
// <= 200 ms): an index of N runs (10,000 by default: 4 units, 3 procedures, 2 specs, every
// verdict and status), written in one transaction (set-up, not the test), then GET /api/runs
// through DaemonApi::handle (no HTTP: the query and its JSON) for the first page, a middle
// page, the last page and filtered pages. Prints p50/p99/max per kind. Measures, never asserts.
// Usage: history_benchmark [RUNS=10000] [REPEATS=200] [DIR=/tmp]
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "../latencies.hpp"
#include "../read_only_launcher.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/storage/run_store.hpp"

namespace {

using namespace wavebench;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

using benchmarks::Latencies;

using NoRuns = benchmarks::ReadOnlyLauncher;

void exec(sqlite3* db, const std::string& sql) {
  char* message = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    std::string text = message ? message : "?";
    sqlite3_free(message);
    throw std::runtime_error(text);
  }
}

// Rows as RunStore writes them, one per minute from 2026-01-01, without run folders.
void fill_index(const fs::path& root, int runs) {
  { storage::RunStore create(root, "bench"); }  // the schema, as the store makes it
  sqlite3* db = nullptr;
  if (sqlite3_open((root / "index.sqlite").c_str(), &db) != SQLITE_OK) {
    throw std::runtime_error("cannot open the index");
  }
  exec(db, "BEGIN");
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db,
                     "INSERT INTO runs (id, started_at, finished_at, unit_serial, procedure, "
                     "status, reason, pass, limits_json, software_version, config_hash, spec) "
                     "VALUES (?1, ?2, ?2, ?3, ?4, ?5, ?6, ?7, '{}', 'bench', 'hash', ?8)",
                     -1, &st, nullptr);
  const char* procedures[] = {"static", "dynamic", "lost-motion"};
  const char* specs[] = {"", "csf-25-100", "sim-seed004"};
  for (int i = 0; i < runs; ++i) {
    const int day = i / 1440, minute = i % 1440;
    char id[32], started[40];
    std::snprintf(id, sizeof id, "2026%02d%02dT%02d%02d00.000000Z", 1 + day / 28, 1 + day % 28,
                  minute / 60, minute % 60);
    std::snprintf(started, sizeof started, "2026-%02d-%02dT%02d:%02d:00.000000Z", 1 + day / 28,
                  1 + day % 28, minute / 60, minute % 60);
    const std::string unit = "SN-" + std::to_string(1000 + i % 4);
    const bool aborted = i % 17 == 0;
    sqlite3_bind_text(st, 1, id, -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 2, started, -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 3, unit.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(st, 4, procedures[i % 3], -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 5, aborted ? "aborted" : "complete", -1, SQLITE_STATIC);
    sqlite3_bind_text(st, 6, aborted ? "operator abort" : "", -1, SQLITE_STATIC);
    if (aborted || i % 5 == 4) {
      sqlite3_bind_null(st, 7);
    } else {
      sqlite3_bind_int(st, 7, i % 7 == 3 ? 0 : 1);
    }
    sqlite3_bind_text(st, 8, specs[i % 3], -1, SQLITE_STATIC);
    if (sqlite3_step(st) != SQLITE_DONE) throw std::runtime_error(sqlite3_errmsg(db));
    sqlite3_reset(st);
  }
  sqlite3_finalize(st);
  exec(db, "COMMIT");
  sqlite3_close(db);
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 10000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 200;
  const fs::path base = argc > 3 ? fs::path(argv[3]) : fs::temp_directory_path();
  const fs::path dir = base / ("wavebench-history-benchmark-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const auto fill_start = Clock::now();
  fill_index(dir / "runs", runs);
  std::printf("index of %d runs written in %.0f ms\n", runs,
              std::chrono::duration<double, std::milli>(Clock::now() - fill_start).count());

  daemon::DaemonSetup setup;
  setup.bench_factory = []() -> std::unique_ptr<bench::Bench> { return nullptr; };  // never started
  setup.launcher = std::make_unique<NoRuns>();
  setup.runs_dir = dir / "runs";
  setup.token = "benchmark-token-0123456789abcdef";
  setup.port = 0;
  int rc = 0;
  {
    daemon::Daemon d(std::move(setup));
    const std::string middle = std::to_string(runs / 2);
    const std::vector<std::pair<const char*, std::string>> pages = {
        {"first page (50)", "/api/runs"},
        {"first page (1000)", "/api/runs?limit=1000"},
        {"middle page (50)", "/api/runs?offset=" + middle},
        {"last page (50)", "/api/runs?offset=" + std::to_string(std::max(0, runs - 50))},
        {"unit", "/api/runs?unit=SN-1002"},
        {"unit + procedure + verdict", "/api/runs?unit=SN-1001&procedure=dynamic&verdict=pass"},
        {"spec + status, middle", "/api/runs?spec=csf-25-100&status=complete&offset=1000"},
        {"verdict fail", "/api/runs?verdict=fail"},
        {"date range (one day)", "/api/runs?from=2026-01-03&to=2026-01-03"},
        {"nothing matches", "/api/runs?unit=SN-NONE"},
    };
    std::printf("GET /api/runs through DaemonApi::handle, %d repeats each:\n", repeats);
    double worst_p99 = 0;
    for (const auto& [what, target] : pages) {
      Latencies l;
      std::size_t total = 0, page = 0;
      for (int i = 0; i < repeats; ++i) {
        daemon::ApiRequest request;
        request.method = "GET";
        request.target = target;
        request.host = "127.0.0.1";
        const auto start = Clock::now();
        const auto reply = d.api().handle(request);
        l.ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        if (reply.status != 200) {
          std::printf("%s: HTTP %d %s\n", what, reply.status, reply.body.dump().c_str());
          rc = 1;
          break;
        }
        total = reply.body["total"].get<std::size_t>();
        page = reply.body["runs"].size();
      }
      const double p99 = l.quantile(0.99);
      worst_p99 = std::max(worst_p99, p99);
      std::printf("  %-28s total %6zu page %4zu  p50 %7.2f ms  p99 %7.2f ms  max %7.2f ms\n", what,
                  total, page, l.quantile(0.5), p99, l.ms.empty() ? 0.0 : l.ms.back());
    }
    std::printf("worst p99 %.2f ms (issue #10 target: <= 200 ms)\n", worst_p99);
  }
  fs::remove_all(dir);
  return rc;
}
