#pragma once
// Keeps the samples a procedure asked for (between start() and stop()) in memory for its
// analysis. Observers run on the bench thread, the same thread as the procedure, so nothing
// here locks.

#include <vector>

#include "wavebench/bench/bench.hpp"

namespace wavebench::procedures {

class SampleRecorder final : public bench::SampleObserver {
 public:
  void start() {
    samples_.clear();
    recording_ = true;
  }
  void stop() { recording_ = false; }
  bool recording() const { return recording_; }
  const std::vector<storage::SyncSample>& samples() const { return samples_; }
  void on_sample(const storage::SyncSample& sample) noexcept override {
    if (recording_) samples_.push_back(sample);
  }

 private:
  std::vector<storage::SyncSample> samples_;
  bool recording_ = false;
};

// Registers an observer for the lifetime of the guard.
class ObserverRegistration {
 public:
  ObserverRegistration(bench::Bench& bench, bench::SampleObserver& observer)
      : bench_(bench), observer_(observer) {
    bench_.add_observer(observer_);
  }
  ~ObserverRegistration() { bench_.remove_observer(observer_); }
  ObserverRegistration(const ObserverRegistration&) = delete;
  ObserverRegistration& operator=(const ObserverRegistration&) = delete;

 private:
  bench::Bench& bench_;
  bench::SampleObserver& observer_;
};

}  // namespace wavebench::procedures
