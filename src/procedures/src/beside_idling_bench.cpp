#include "beside_idling_bench.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <future>
#include <system_error>

namespace wavebench::procedures {

void run_beside_idling_bench(bench::Bench& bench, const std::function<void()>& work) {
  std::future<void> done;
  try {
    done = std::async(std::launch::async, [&work] {
      // Below the bench thread (Linux nice is per thread, inherited by threads it starts): on a
      // busy machine the loop's turn comes first. Failing to lower it changes nothing else.
      (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
      work();
    });
  } catch (const std::system_error&) {
    work();  // no thread to be had: done here, the loop held meanwhile as before
    return;
  }
  // The daemon's idle slice: on the simulated clock idle_for() returns early, the rest of the
  // slice is waited.
  constexpr auto kSlice = std::chrono::milliseconds(20);
  while (done.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    const auto start = std::chrono::steady_clock::now();
    try {
      bench.idle_for(std::chrono::duration<double>(kSlice).count());
    } catch (const std::exception&) {
      // Idling never moves anything; a bench that cannot idle leaves the work to finish.
    }
    const auto spent = std::chrono::steady_clock::now() - start;
    if (spent < kSlice) done.wait_for(kSlice - spent);
  }
  done.get();
}

}  // namespace wavebench::procedures
