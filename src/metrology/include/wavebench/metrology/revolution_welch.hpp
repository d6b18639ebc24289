#pragma once
// Welch's average over every whole output revolution of a dynamic-TE record, however long
// (issue #12): each revolution of the order grid (P points) is transformed with a Hann window
// and the bins' power averaged, so a steady line reads its amplitude and noise averages down.
// The record's grid is capped for the whole-record spectrum; this sees every revolution.
//
// put() runs where the record is fed, the acquisition thread during a run: it copies the point
// into one of a few buffers made up front and hands a full revolution over lock-free to a worker
// thread that transforms it (an FFT of a revolution takes about a SYNC period: not on the
// acquisition thread). A revolution that finds no free buffer is left out of the average and
// counted. Without a worker (a record analysed after the fact) a full revolution is
// transformed where put() runs.

#include <atomic>
#include <boost/lockfree/spsc_queue.hpp>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"

namespace wavebench::metrology {

struct RevolutionAverage {
  std::vector<double> amplitude;  // bin k at k · resolution [orders of the output]
  double resolution = 0;
  std::size_t revolutions = 0;  // averaged
  std::size_t dropped = 0;      // whole revolutions left out (no free buffer)
};

class RevolutionWelch {
 public:
  enum class Transform { kOnWorker, kWherePut };
  // `analyser`: the caller's, for kWherePut (its plans reused across records); the worker has
  // its own. Throws std::invalid_argument for fewer than 8 points per revolution.
  RevolutionWelch(std::size_t points_per_revolution, Transform where,
                  analysis::SpectrumAnalyser* analyser = nullptr);
  ~RevolutionWelch();
  RevolutionWelch(const RevolutionWelch&) = delete;
  RevolutionWelch& operator=(const RevolutionWelch&) = delete;

  // The next grid point (point j of revolution j / P). Allocates nothing with a worker.
  void put(double value) noexcept;
  // Every full revolution put, averaged; a partial last one is left out. Stops the worker after
  // it has taken every revolution handed over. Call once, after the last put().
  RevolutionAverage finish();

 private:
  static constexpr std::size_t kBuffers = 4;
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  void transform(const std::vector<double>& revolution);
  void take_ready();

  std::size_t points_;
  Transform where_;
  std::vector<std::vector<double>> buffers_;
  boost::lockfree::spsc_queue<std::size_t> ready_{kBuffers + 1};  // put() -> worker
  boost::lockfree::spsc_queue<std::size_t> free_{kBuffers + 1};   // worker -> put()
  // put()'s side.
  std::size_t filling_ = kNone;
  std::size_t index_ = 0;  // of the next point
  std::atomic<std::size_t> dropped_{0};
  // The transform's side.
  analysis::SpectrumAnalyser own_analyser_;
  analysis::SpectrumAnalyser* analyser_;
  std::vector<double> power_;
  double resolution_ = 0;
  std::size_t revolutions_ = 0;
  std::exception_ptr failure_;
  std::jthread worker_;
};

}  // namespace wavebench::metrology
