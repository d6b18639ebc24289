// The samples API on a long run (issue #12 item 4; target: on a 3.6 M-sample log a
// 10,000-sample page from the middle in <= 20 ms, p99 of 100 requests). A synthetic run
// (synthetic_run.hpp) is added to a RunStore through its API, then
// GET /api/runs/{id}/samples?from=..&limit=10000 goes through DaemonApi::handle (no HTTP: the
// page read and its JSON) and the body's text as the server sends it is timed with it, beside
// the process's CPU time per request (the read runs at nice +10: on a loaded machine its wall
// time waits for the CPU). Pages from the middle, and for comparison the first and the last.
// Prints p50/p99/max. Measures, never asserts.
// Usage: samples_page_benchmark [SAMPLES=3600000] [REQUESTS=100] [DIR=/tmp]
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "../latencies.hpp"
#include "../read_only_launcher.hpp"
#include "synthetic_run.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/storage/run_store.hpp"

namespace {

using namespace wavebench;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
using benchmarks::Latencies;

using NoRuns = benchmarks::ReadOnlyLauncher;

// CPU time of the process: beside the wall time, what a request costs when the machine is
// shared. The page is read on the daemon's reader thread at nice +10 (LowPriorityReads), so a
// loaded machine shows in the wall time, not here; nothing else in the process runs meanwhile.
double process_cpu_ms() {
  timespec ts{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t samples = argc > 1 ? std::stoul(argv[1]) : 3'600'000;
  const int requests = argc > 2 ? std::atoi(argv[2]) : 100;
  const fs::path base = argc > 3 ? fs::path(argv[3]) : fs::temp_directory_path();
  const fs::path dir = base / ("wavebench-samples-page-benchmark-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::string id;
  {
    const auto start = Clock::now();
    storage::RunStore store(dir / "runs", "benchmark");
    benchmarks::SyntheticRunSpec spec;
    spec.samples = samples;
    spec.twin_csv = false;
    id = benchmarks::add_synthetic_run(store, spec);
    std::printf("run %s of %zu samples (%.0f MB of log) written in %.1f s\n", id.c_str(), samples,
                static_cast<double>(fs::file_size(store.paths(id).samples)) / 1e6,
                std::chrono::duration<double>(Clock::now() - start).count());
  }
  daemon::DaemonSetup setup;
  setup.bench_factory = []() -> std::unique_ptr<bench::Bench> { return nullptr; };
  setup.launcher = std::make_unique<NoRuns>();
  setup.runs_dir = dir / "runs";
  setup.token = "benchmark-token-0123456789abcdef";
  setup.port = 0;
  int rc = 0;
  {
    daemon::Daemon d(std::move(setup));
    const std::size_t page = 10'000;
    const std::vector<std::pair<const char*, std::size_t>> pages = {
        {"middle", samples / 2 - page / 2},
        {"first", 0},
        {"last", samples > page ? samples - page : 0},
    };
    std::printf(
        "GET /api/runs/%s/samples?limit=%zu through DaemonApi::handle, %d "
        "requests each:\n",
        id.c_str(), page, requests);
    for (const auto& [what, from] : pages) {
      Latencies handle, total, cpu;
      std::size_t returned = 0, bytes = 0;
      for (int i = 0; i < requests; ++i) {
        daemon::ApiRequest request;
        request.method = "GET";
        request.target = "/api/runs/" + id + "/samples?from=" + std::to_string(from) +
                         "&limit=" + std::to_string(page);
        request.host = "127.0.0.1";
        const double cpu_start = process_cpu_ms();
        const auto start = Clock::now();
        const auto reply = d.api().handle(request);
        const auto handled = Clock::now();
        const std::string body = reply.raw_body ? *reply.raw_body : daemon::response_text(reply);
        const auto end = Clock::now();
        cpu.ms.push_back(process_cpu_ms() - cpu_start);
        handle.ms.push_back(std::chrono::duration<double, std::milli>(handled - start).count());
        total.ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
        if (reply.status != 200) {
          std::printf("%s: HTTP %d %s\n", what, reply.status, body.c_str());
          rc = 1;
          break;
        }
        if (i + 1 == requests) returned = nlohmann::json::parse(body)["samples"].size();
        bytes = body.size();
      }
      // Quantiles first: they sort, and the arguments of one call have no order.
      const double h50 = handle.quantile(0.5), h99 = handle.quantile(0.99);
      const double t50 = total.quantile(0.5), t99 = total.quantile(0.99);
      const double worst = total.ms.empty() ? 0.0 : total.ms.back();
      const double c50 = cpu.quantile(0.5), c99 = cpu.quantile(0.99);
      std::printf("  %-6s from %8zu: %5zu samples, %4.2f MB of JSON\n", what, from, returned,
                  static_cast<double>(bytes) / 1e6);
      std::printf(
          "         wall: handle p50 %6.2f p99 %6.2f ms; with the body's text p50 %6.2f "
          "p99 %6.2f max %6.2f ms\n",
          h50, h99, t50, t99, worst);
      std::printf("         CPU of the process, with the text: p50 %6.2f p99 %6.2f ms\n", c50, c99);
    }
    std::printf(
        "(issue #12 target: a 10,000-sample page from the middle in <= 20 ms, p99 of 100)\n");
  }
  fs::remove_all(dir);
  return rc;
}
