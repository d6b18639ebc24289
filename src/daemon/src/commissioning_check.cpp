#include <stdexcept>

#include "wavebench/bench/bench_check.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/daemon/bench_thread.hpp"

namespace wavebench::daemon {

BenchCheck make_commissioning_check() {
  return [](bench::Bench& bench) {
    auto* canopen = bench::canopen_bench_of(bench);
    if (!canopen) throw std::runtime_error("the bench is not a CANopen bench");
    // The daemon connects the bench itself (and reconnects it on a reset): the check does not.
    bench::CheckOptions options;
    options.connect = false;
    return bench::check_report_json(bench::check_bench(*canopen, options));
  };
}

}  // namespace wavebench::daemon
