// The daemon under read load (issue #8): wavebenchd in process on the in-process simulated
// bench (real clock, its event loop turning between runs), one run whose samples.wbs holds N
// records (16 M by default, 1.5 GB), and two clients paging through it while a third asks for
// /api/status every 20 ms. Prints status latency idle and under load (p50/p99/max and the
// ratio), the page latency of each reader (10,000-sample pages, from the middle too), and
// peak RSS. Measures, never asserts.
// Usage: daemon_read_benchmark [RECORDS=16000000] [SECONDS=20] [DIR=/tmp]
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/daemon/daemon.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace {

using namespace wavebench;
using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
constexpr const char* kToken = "benchmark-token-0123456789abcdef";

struct Latencies {
  std::vector<double> ms;
  void add(Clock::time_point start) {
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  double quantile(double q) {
    if (ms.empty()) return 0;
    std::sort(ms.begin(), ms.end());
    return ms[std::min(ms.size() - 1,
                       static_cast<std::size_t>(q * static_cast<double>(ms.size())))];
  }
  void print(const char* what) {
    std::printf("%-34s n=%6zu  p50 %8.2f ms  p99 %8.2f ms  max %8.2f ms\n", what, ms.size(),
                quantile(0.5), quantile(0.99),
                ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end()));
  }
};

std::string write_long_run(storage::RunStore& store, std::uint64_t records) {
  const auto id = store.create_run("dynamic", "SN-BENCH", "name: sim\n");
  storage::SampleLogWriterOptions options;
  options.checkpoint_every_records = 0;  // one fdatasync at close: this is set-up, not the test
  storage::SampleLogWriter writer(store.paths(id).samples, options);
  storage::SyncSample s;
  s.flags = storage::kAllChannelsValid;
  for (std::uint64_t i = 0; i < records; ++i) {
    s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
    s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
    s.theta_in_rad = 1e-3 * static_cast<double>(i);
    s.theta_out_rad = s.theta_in_rad / 100;
    writer.append(s);
  }
  writer.close();
  store.finish_run(id, storage::RunStatus::kComplete);
  return id;
}

Latencies poll_status(const daemon::DaemonClient& client, double seconds) {
  Latencies l;
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < end) {
    const auto start = Clock::now();
    const auto reply = client.get("/api/status");
    if (reply.ok()) l.add(start);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return l;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t records = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 16'000'000;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 20.0;
  const fs::path base = argc > 3 ? argv[3] : fs::temp_directory_path();
  const auto dir = base / ("wavebench-daemon-read-" + std::to_string(::getpid()));
  fs::create_directories(dir);

  std::string id;
  const auto set_up = Clock::now();
  {
    storage::RunStore store(dir / "runs", "benchmark");
    id = write_long_run(store, records);
  }
  std::printf("log of %llu records (%.2f GB) written in %.1f s\n",
              static_cast<unsigned long long>(records),
              static_cast<double>(fs::file_size(dir / "runs" / id / "samples.wbs")) / 1e9,
              std::chrono::duration<double>(Clock::now() - set_up).count());

  auto config = bench::default_simulated_bench_config();
  config.clock = bench::BenchClockKind::kReal;
  config.description.simulated_clock = false;
  daemon::DaemonSetup setup;
  setup.bench_factory = [config] { return bench::make_bench(config); };
  struct NoRuns : daemon::RunLauncher {
    procedures::RunOutcome launch(bench::Bench&, storage::RunStore&, const procedures::RunRequest&,
                            const procedures::ProgressSink&) override {
      throw std::invalid_argument("this benchmark starts no runs");
    }
    void check(const procedures::RunRequest&, const bench::BenchDescription&, std::size_t,
               const fs::path&) const override {}
  };
  setup.launcher = std::make_unique<NoRuns>();
  setup.runs_dir = dir / "runs";
  setup.port = 0;
  setup.token = kToken;
  daemon::Daemon d(std::move(setup));
  d.start();
  const std::string url = "http://127.0.0.1:" + std::to_string(d.port());
  const daemon::DaemonClient client(url, kToken);

  auto idle = poll_status(client, std::min(5.0, seconds / 2));

  std::atomic<bool> stop{false};
  std::vector<Latencies> pages(2);
  std::vector<std::uint64_t> busy(2, 0);
  std::vector<std::thread> readers;
  for (int r = 0; r < 2; ++r) {
    readers.emplace_back([&, r] {
      const daemon::DaemonClient reader(url, "");
      // The two readers start at the beginning and in the middle of the log.
      std::uint64_t from = r == 0 ? 0 : records / 2;
      while (!stop) {
        const auto start = Clock::now();
        const auto reply = reader.get("/api/runs/" + id + "/samples?from=" + std::to_string(from) +
                                      "&limit=10000");
        if (reply.status == 503) {
          ++busy[static_cast<std::size_t>(r)];
          continue;
        }
        if (!reply.ok()) break;
        pages[static_cast<std::size_t>(r)].add(start);
        from += 10000;
        if (from >= records) from = 0;
      }
    });
  }
  auto loaded = poll_status(client, seconds);
  stop = true;
  for (auto& t : readers) t.join();
  d.shutdown("benchmark done");

  idle.print("status, idle");
  loaded.print("status, two readers paging");
  pages[0].print("page of 10,000 from the start");
  pages[1].print("page of 10,000 from the middle");
  std::printf("status p99 under load / idle: %.2f; pages refused busy: %llu, %llu\n",
              loaded.quantile(0.99) / std::max(1e-9, idle.quantile(0.99)),
              static_cast<unsigned long long>(busy[0]), static_cast<unsigned long long>(busy[1]));
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  std::printf("peak RSS %.0f MB\n", static_cast<double>(u.ru_maxrss) / 1024.0);
  fs::remove_all(dir);
  return 0;
}
