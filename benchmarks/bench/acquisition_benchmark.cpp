// The acquisition benchmark (issue #5): the in-process simulated bench on the real clock at
// the configured SYNC rate (1 kHz by default) for a given time, the input turning at 100 rpm
// under a brake load, every sample going to a sample log on disk and to the twin beside the
// bench, as in a run. Prints samples lost (SYNCs sent − records on disk), incomplete samples,
// SYNC lateness p50/p99/max, the twin's lag and drops, and CPU use.
// Usage: acquisition_benchmark [SECONDS=600] [CONFIG=sim]
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/storage/sample_log.hpp"
#include "wavebench/twin/twin_beside_bench.hpp"

namespace {

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

class GapObserver : public wavebench::bench::SampleObserver {
 public:
  void on_sample(const wavebench::storage::SyncSample& s) noexcept override {
    if (have_ && s.sync_counter != previous_ % 240 + 1) ++gaps;
    previous_ = s.sync_counter;
    for (int bit = 0; bit < 6; ++bit)
      if ((s.flags & (1u << bit)) == 0) ++missing[bit];
    have_ = true;
  }
  std::uint64_t gaps = 0;
  std::uint64_t missing[6] = {};  // per channel, in SampleFlag bit order

 private:
  bool have_ = false;
  std::uint32_t previous_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace wavebench::bench;
  const double seconds = argc > 1 ? std::atof(argv[1]) : 600.0;
  auto config = bench_config_from_argument(argc > 2 ? argv[2] : "sim");
  config.clock = BenchClockKind::kReal;
  config.description.simulated_clock = false;
  auto bench = make_bench(config);
  GapObserver gaps;
  bench->add_observer(gaps);
  const auto log_path = std::filesystem::temp_directory_path() /
                        ("wavebench-acquisition-" + std::to_string(::getpid()) + ".wbs");
  class LogObserver : public SampleObserver {
   public:
    explicit LogObserver(const std::filesystem::path& p) : writer(p) {}
    void on_sample(const wavebench::storage::SyncSample& s) noexcept override {
      try {
        writer.append(s);
        writer.flush_if_due();
      } catch (...) {
        ++failures;
      }
    }
    wavebench::storage::SampleLogWriter writer;
    std::uint64_t failures = 0;
  } log(log_path);
  wavebench::twin::TwinBesideBench twin(bench->description().twin_gear, bench->description().sense);
  bench->connect();
  bench->set_brake_torque(10.0);
  bench->run_input_velocity(100 * 2 * M_PI / 60);
  const double cpu0 = cpu_seconds();
  const auto real0 = std::chrono::steady_clock::now();
  const auto s0 = bench->acquisition_stats();
  bench->add_observer(log);
  bench->add_observer(twin);
  bench->wait_for(seconds);
  bench->remove_observer(twin);
  bench->remove_observer(log);
  const auto s = bench->acquisition_stats();
  const double real =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - real0).count();
  const double cpu = cpu_seconds() - cpu0;
  bench->stop_motion();
  bench->disconnect();
  log.writer.close();
  const auto on_disk = wavebench::storage::read_sample_log(log_path);
  std::filesystem::remove(log_path);
  const auto& tw = twin.finish();
  const auto expected = static_cast<std::uint64_t>(real / config.description.sync_period_s);
  std::printf("acquisition benchmark: %.1f s at %.0f Hz (real clock, in-process simulated bench)\n",
              real, 1 / config.description.sync_period_s);
  std::printf("  SYNCs sent %llu (deadlines %llu), samples %llu, incomplete %llu, gaps %llu\n",
              static_cast<unsigned long long>(s.syncs_sent - s0.syncs_sent),
              static_cast<unsigned long long>(expected),
              static_cast<unsigned long long>(s.samples - s0.samples),
              static_cast<unsigned long long>(s.incomplete_samples - s0.incomplete_samples),
              static_cast<unsigned long long>(gaps.gaps));
  std::printf("  SYNC skipped %llu, late %llu; lateness p50 %.1f us, p99 %.1f us, max %.1f us\n",
              static_cast<unsigned long long>(s.sync_skipped),
              static_cast<unsigned long long>(s.sync_late), s.sync_lateness_p50_s * 1e6,
              s.sync_lateness_p99_s * 1e6, s.sync_lateness_max_s * 1e6);
  std::printf(
      "  missing per channel: theta_in %llu, theta_out %llu, speed %llu, torque %llu, "
      "brake current %llu, brake torque %llu\n",
      static_cast<unsigned long long>(gaps.missing[0]),
      static_cast<unsigned long long>(gaps.missing[1]),
      static_cast<unsigned long long>(gaps.missing[2]),
      static_cast<unsigned long long>(gaps.missing[3]),
      static_cast<unsigned long long>(gaps.missing[4]),
      static_cast<unsigned long long>(gaps.missing[5]));
  std::printf("  samples on disk %llu of %llu handed over (lost %lld, write failures %llu)\n",
              static_cast<unsigned long long>(on_disk.samples.size()),
              static_cast<unsigned long long>(log.writer.records_appended()),
              static_cast<long long>(log.writer.records_appended()) -
                  static_cast<long long>(on_disk.samples.size()),
              static_cast<unsigned long long>(log.failures));
  std::printf(
      "  twin: %llu received, %llu dropped, %llu predicted; lag p50 %.1f ms, p99 %.1f ms, "
      "max %.1f ms; twin thread CPU %.2f s%s%s\n",
      static_cast<unsigned long long>(tw.samples_received),
      static_cast<unsigned long long>(tw.samples_dropped),
      static_cast<unsigned long long>(tw.samples_predicted), tw.lag.p50_s * 1e3, tw.lag.p99_s * 1e3,
      tw.lag.max_s * 1e3, tw.thread_cpu_s, tw.error.empty() ? "" : "; error: ", tw.error.c_str());
  std::printf("  CPU %.1f %% of one core (%.2f s, twin thread included), bus load %.0f %%\n",
              100 * cpu / real, cpu, s.bus_load * 100);
  return 0;
}
