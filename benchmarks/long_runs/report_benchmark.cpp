// The report of a long run (issue #12 item 3; target: a one-hour run's report in <= 3 s, its
// memory flat with the record's length). Synthesises dynamic run folders of the given sizes
// (synthetic_run.hpp: samples.wbs, twin.csv of as many rows, results.json from RESULTS when
// given, e.g. that of a real `wavebench run dynamic --bench sim --revolutions 2`), then writes
// each folder's report in a child process of its own and prints its wall time and peak RSS
// (wait4) and the ratios between the last and the first. Files are in the page cache (just
// written). Measures, never asserts.
// Usage: report_benchmark [SIZES=120000,3600000] [DIR=/tmp] [RESULTS=results.json] [keep]
// (RESULTS "-": the built-in results; "keep": leave the folders, e.g. to time another build's
// `wavebench report` on them)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "synthetic_run.hpp"
#include "wavebench/report/run_report.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace wavebench;

struct Measured {
  double wall_s = 0, cpu_s = 0, peak_mb = 0;
  int status = 0;
};

// The report in a child process, so that its peak RSS is its own.
Measured report_in_child(const fs::path& dir) {
  const auto start = Clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      const auto report = report::write_run_report(dir);
      std::_Exit(report.plots.empty() ? 2 : 0);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "report of %s: %s\n", dir.c_str(), e.what());
      std::_Exit(1);
    }
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  Measured m;
  m.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  m.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  // CPU time beside the wall: on a machine shared with other work the wall is not the report's.
  const auto seconds = [](const timeval& tv) {
    return static_cast<double>(tv.tv_sec) + 1e-6 * static_cast<double>(tv.tv_usec);
  };
  m.cpu_s = seconds(usage.ru_utime) + seconds(usage.ru_stime);
  m.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  return m;
}

double own_rss_mb() {
  std::ifstream in("/proc/self/statm");
  long pages = 0, resident = 0;
  in >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / 1048576.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  std::stringstream list(argc > 1 ? argv[1] : "120000,3600000");
  for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::stoul(item));
  const fs::path base = argc > 2 ? fs::path(argv[2]) : fs::temp_directory_path();
  nlohmann::json results_template;
  if (argc > 3 && std::string(argv[3]) != "-") std::ifstream(argv[3]) >> results_template;
  const fs::path work = base / ("wavebench-report-benchmark-" + std::to_string(::getpid()));
  std::printf("%10s %10s %10s %10s %10s %10s %6s\n", "samples", "setup [s]", "files [MB]",
              "wall [s]", "CPU [s]", "peak [MB]", "exit");
  std::vector<Measured> rows;
  int rc = 0;
  for (const std::size_t n : sizes) {
    benchmarks::SyntheticRunSpec spec;
    spec.samples = n;
    spec.results_template = results_template;
    const fs::path dir = work / std::to_string(n);
    const auto setup_start = Clock::now();
    benchmarks::write_synthetic_run_files(dir, spec);
    const double setup = std::chrono::duration<double>(Clock::now() - setup_start).count();
    const Measured m = report_in_child(dir);
    rows.push_back(m);
    rc |= m.status;
    std::printf(
        "%10zu %10.1f %10.0f %10.2f %10.2f %10.1f %6d\n", n, setup,
        static_cast<double>(fs::file_size(dir / "samples.wbs") + fs::file_size(dir / "twin.csv")) /
            1e6,
        m.wall_s, m.cpu_s, m.peak_mb, m.status);
    std::fflush(stdout);
  }
  std::printf("(the parent's RSS at fork, counted in each child's peak: %.1f MB)\n", own_rss_mb());
  if (rows.size() > 1) {
    std::printf(
        "last/first: samples x%.0f, wall x%.2f, CPU x%.2f, peak RSS x%.2f (issue #12: a "
        "one-hour run's report in <= 3 s, memory flat)\n",
        static_cast<double>(sizes.back()) / static_cast<double>(sizes.front()),
        rows.back().wall_s / rows.front().wall_s, rows.back().cpu_s / rows.front().cpu_s,
        rows.back().peak_mb / rows.front().peak_mb);
  }
  if (argc > 4 && std::string(argv[4]) == "keep") {
    std::printf("folders kept under %s\n", work.c_str());
  } else {
    fs::remove_all(work);
  }
  return rc;
}
