#pragma once
// Real-time scheduling for the thread that produces SYNC and assembles samples (bench.md §1):
// SCHED_FIFO and locked memory where the process is permitted them. Where it is not (no
// CAP_SYS_NICE / CAP_IPC_LOCK, a container, an RLIMIT), the bench runs on ordinary scheduling:
// the caller logs the message, it is never fatal. Only for a bench on the real clock: on the
// simulated clock the bench thread runs flat out and must not starve the rest of the machine.

#include <string>

namespace wavebench::daemon {

struct RealtimeScheduling {
  bool fifo = false;           // the calling thread runs SCHED_FIFO at the priority asked
  bool memory_locked = false;  // mlockall(MCL_CURRENT | MCL_FUTURE) succeeded
  std::string message;         // what was granted and what was refused, with the errno text
};

// Applies to the calling thread (scheduling) and the whole process (memory). Threads the caller
// starts afterwards run on ordinary scheduling (SCHED_RESET_ON_FORK); note that glibc's
// pthread_getschedparam reports the parent's cached policy for them, sched_getscheduler(0)
// reports what the kernel applies.
RealtimeScheduling request_realtime_scheduling(int fifo_priority = 40);

}  // namespace wavebench::daemon
