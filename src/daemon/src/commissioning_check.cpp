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
    // Nor does it move anything: CheckOptions::motion (the units check's bounded motion, issue
    // #20) stays off here; `wavebench bench check --motion` is where an operator asks for it.
    bench::CheckOptions options;
    options.connect = false;
    return bench::check_report_json(bench::check_bench(*canopen, options));
  };
}

}  // namespace wavebench::daemon
