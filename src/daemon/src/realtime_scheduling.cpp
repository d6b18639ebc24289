#include "wavebench/daemon/realtime_scheduling.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace wavebench::daemon {

RealtimeScheduling request_realtime_scheduling(int fifo_priority) {
  RealtimeScheduling r;
  sched_param param{};
  param.sched_priority = fifo_priority;
  // SCHED_RESET_ON_FORK: the threads this one starts (the twin, the sample log's writer, the
  // post-run analysis, the brake's heartbeat) run on ordinary scheduling, not at this priority.
  // Inherited, their seconds of CPU starved the machine's other threads: a simulated brake
  // waiting for the CPU missed its watchdog and tripped the bench after a run.
  const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO | SCHED_RESET_ON_FORK, &param);
  if (rc == 0) {
    r.fifo = true;
    r.message = "SCHED_FIFO priority " + std::to_string(fifo_priority);
  } else {
    r.message = std::string("SCHED_FIFO refused (") + std::strerror(rc) + ")";
  }
  if (::mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
    r.memory_locked = true;
    r.message += ", memory locked";
  } else {
    r.message += std::string(", mlockall refused (") + std::strerror(errno) + ")";
  }
  return r;
}

}  // namespace wavebench::daemon
