#pragma once
// A mutex for data the SCHED_FIFO acquisition thread shares with ordinary threads (the brake's
// heartbeat supervisor, a simulated device's server). With std::mutex, an ordinary thread
// preempted while holding the lock keeps the real-time thread waiting for as long as the
// machine is busy elsewhere (priority inversion: a loaded machine showed 0.24-0.3 s SYNC
// stalls). PTHREAD_PRIO_INHERIT lends the waiter's priority to the holder until it unlocks.
// Hand-written: neither the standard library nor Boost offers a priority-inheriting mutex.

#include <pthread.h>

#include <cerrno>
#include <system_error>

namespace wavebench::realtime {

class PriorityInheritingMutex {
 public:
  PriorityInheritingMutex() {
    pthread_mutexattr_t attr;
    pthread_mutexattr_init(&attr);
    pthread_mutexattr_setprotocol(&attr, PTHREAD_PRIO_INHERIT);
    const int rc = pthread_mutex_init(&mutex_, &attr);
    pthread_mutexattr_destroy(&attr);
    if (rc != 0) throw std::system_error(rc, std::generic_category(), "pthread_mutex_init");
  }
  ~PriorityInheritingMutex() { pthread_mutex_destroy(&mutex_); }
  PriorityInheritingMutex(const PriorityInheritingMutex&) = delete;
  PriorityInheritingMutex& operator=(const PriorityInheritingMutex&) = delete;

  void lock() {
    const int rc = pthread_mutex_lock(&mutex_);
    if (rc != 0) throw std::system_error(rc, std::generic_category(), "pthread_mutex_lock");
  }
  bool try_lock() noexcept { return pthread_mutex_trylock(&mutex_) == 0; }
  void unlock() noexcept { pthread_mutex_unlock(&mutex_); }

 private:
  pthread_mutex_t mutex_;
};

}  // namespace wavebench::realtime
