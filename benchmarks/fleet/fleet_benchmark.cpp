// A trend and an SPC query over the runs of one gear model in a results store of N runs
// (10,000 by default: 4 benches, 2 gear models, every procedure's figures), on a PostgreSQL 15
// server this benchmark starts itself, or (STORE=sqlite) a bench's own SQLite store in a
// temporary file. Publishing is set-up (timed once, printed), the queries are the measurement:
// p50/p99/max over REPEATS. Measures, never asserts.
// Usage: fleet_benchmark [RUNS=10000] [REPEATS=50] [STORE=postgresql|sqlite]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "../latencies.hpp"
#include "postgres_server.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"

namespace {

using namespace wavebench;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

using benchmarks::Latencies;

// A run as summarise_run would give it, without a run folder: index row and figures.
fleet::RunSummary synthetic(int i, std::mt19937& rng) {
  std::normal_distribution<double> noise(0, 1);
  fleet::RunSummary s;
  s.bench = "bench-" + std::to_string(i % 4);
  char id[40];
  std::snprintf(id, sizeof id, "20260101T%06d.%06dZ", i / 1000000, i % 1000000);
  s.run_id = id;
  s.station = "line-1";
  s.unit_serial = "U-" + std::to_string(100000 + i);
  s.gear_model = i % 2 ? "CSF-25-100-2A-GR" : "CSG-32-160";
  s.spec = i % 2 ? "csf-25-100" : "csg-32-160";
  s.spec_version = "0123456789abcdef";
  s.procedure = "static";
  s.status = i % 50 == 0 ? "aborted" : "complete";
  s.verdict = "PASS";
  s.pass = true;
  // One run a minute from 2026-01-01.
  const int minutes = i;
  char at[40];
  std::snprintf(at, sizeof at, "2026-01-%02dT%02d:%02d:00.000000Z", 1 + minutes / 1440,
                (minutes / 60) % 24, minutes % 60);
  s.started_at = at;
  s.finished_at = at;
  s.software_version = "0.1.0";
  s.config_hash = "hash";
  s.samples_ref = s.bench + ":" + s.run_id + "/samples.wbs";
  s.figures = {
      {"static_te_p2p", 0.8 + 0.04 * noise(rng)}, {"static_lost_motion", 0.4 + 0.02 * noise(rng)},
      {"lost_motion", 0.9 + 0.05 * noise(rng)},   {"k1", 3.2e4 + 500 * noise(rng)},
      {"dynamic_te_p2p", 60 + 3 * noise(rng)},    {"dynamic_te_rms", 15 + noise(rng)}};
  s.static_passes = {{"forward", 0, s.figures["static_te_p2p"], 0.1, 0.2},
                     {"reverse", 0, s.figures["static_te_p2p"] - 0.1, 0.1, 0.2}};
  s.limits = {{"static_p2p_arcmin", 1.0}, {"min_stiffness_nm_per_rad", 3.1e4}};
  s.results = {{"bench", s.bench}, {"note", "synthetic"}};
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 10000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 50;
  const std::string kind = argc > 3 ? argv[3] : "postgresql";
  try {
    std::unique_ptr<fleet::testing::PostgresServer> server;
    std::unique_ptr<fleet::ResultsStore> own;
    std::filesystem::path sqlite_dir;
    if (kind == "sqlite") {
      sqlite_dir = std::filesystem::temp_directory_path() /
                   ("wavebench-fleet-benchmark." + std::to_string(::getpid()));
      std::filesystem::remove_all(sqlite_dir);
      std::filesystem::create_directories(sqlite_dir);
      own = std::make_unique<fleet::SqliteResultsStore>(sqlite_dir / "index.sqlite");
    } else {
      server = std::make_unique<fleet::testing::PostgresServer>();
      server->create_database("wavebench");
      own = std::make_unique<fleet::PostgresResultsStore>(server->config("wavebench"));
    }
    fleet::ResultsStore& store = *own;
    std::printf("store: %s\n", kind == "sqlite" ? "sqlite (a bench's own)" : "postgresql");
    std::mt19937 rng(42);
    auto t0 = Clock::now();
    for (int i = 0; i < runs; ++i) store.publish(synthetic(i, rng));
    std::printf("published %d runs in %.1f s (%.2f ms per run, one transaction each)\n", runs,
                ms_since(t0) / 1e3, ms_since(t0) / runs);

    struct Case {
      const char* name;
      fleet::FigureQuery query;
      bool spc;
    };
    fleet::FigureQuery all;
    all.figure = "static_te_p2p";
    all.gear_model = "CSF-25-100-2A-GR";
    fleet::FigureQuery one_pass = all;
    one_pass.direction = "forward";
    one_pass.load_nm = 0;
    fleet::FigureQuery per_bench = all;
    per_bench.figure = "k1";
    per_bench.bench = "bench-1";
    fleet::FigureQuery last500 = all;
    last500.last = 500;
    const std::vector<Case> cases = {
        {"trend static_te_p2p, every run of the model", all, false},
        {"trend static_te_p2p forward 0 N*m (static table)", one_pass, false},
        {"trend k1 of one bench", per_bench, false},
        {"trend static_te_p2p, newest 500", last500, false},
        {"spc static_te_p2p, every run of the model", all, true}};
    for (const auto& c : cases) {
      Latencies lat;
      std::size_t points = 0;
      for (int r = 0; r < repeats; ++r) {
        t0 = Clock::now();
        points = c.spc ? store.spc(c.query, {}).points.size() : store.trend(c.query).size();
        lat.ms.push_back(ms_since(t0));
      }
      std::printf("%-50s %5zu points  p50 %7.2f ms  p99 %7.2f ms  max %7.2f ms\n", c.name, points,
                  lat.quantile(0.5), lat.quantile(0.99), lat.quantile(1.0));
    }
    own.reset();
    if (!sqlite_dir.empty()) std::filesystem::remove_all(sqlite_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fleet_benchmark: %s\n", e.what());
    return 1;
  }
  return 0;
}
