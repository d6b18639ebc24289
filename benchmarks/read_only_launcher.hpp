#pragma once
// A run launcher for benchmarks that only read a daemon's run store (history, samples pages):
// a run asked for is refused, never started.

#include <filesystem>
#include <stdexcept>

#include "wavebench/daemon/daemon.hpp"

namespace wavebench::benchmarks {

class ReadOnlyLauncher : public daemon::RunLauncher {
 public:
  procedures::RunOutcome launch(bench::Bench&, storage::RunStore&, const procedures::RunRequest&,
                          const procedures::ProgressSink&) override {
    throw std::invalid_argument("benchmark: this daemon only reads, it runs nothing");
  }
  void check(const procedures::RunRequest&, const bench::BenchDescription&, std::size_t,
             const std::filesystem::path&) const override {}
};

}  // namespace wavebench::benchmarks
