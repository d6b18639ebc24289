#include "wavebench/metrology/revolution_welch.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wavebench::metrology {

RevolutionWelch::RevolutionWelch(std::size_t points_per_revolution, Transform where,
                                 analysis::SpectrumAnalyser* analyser)
    : points_(points_per_revolution),
      where_(where),
      analyser_(analyser && where == Transform::kWherePut ? analyser : &own_analyser_) {
  if (points_ < 8) {
    throw std::invalid_argument("revolution Welch: " + std::to_string(points_) +
                                " points per revolution; expected at least 8");
  }
  buffers_.assign(where_ == Transform::kOnWorker ? kBuffers : 1, std::vector<double>(points_));
  if (where_ == Transform::kWherePut) {
    filling_ = 0;
    return;
  }
  for (std::size_t i = 0; i < kBuffers; ++i) free_.push(i);
  worker_ = std::jthread([this](std::stop_token stop) {
    // A revolution lasts a second or more; polling every few milliseconds keeps the buffers
    // free without a lock or a wake-up shared with the acquisition thread.
    while (!stop.stop_requested()) {
      take_ready();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  });
}

RevolutionWelch::~RevolutionWelch() {
  if (worker_.joinable()) {
    worker_.request_stop();
    worker_.join();
  }
}

void RevolutionWelch::put(double value) noexcept {
  const std::size_t j = index_ % points_;
  ++index_;
  if (where_ == Transform::kWherePut) {
    buffers_[0][j] = value;
    if (j + 1 == points_) {
      try {
        transform(buffers_[0]);
      } catch (...) {
        if (!failure_) failure_ = std::current_exception();
      }
    }
    return;
  }
  if (j == 0) {
    std::size_t b = kNone;
    filling_ = free_.pop(b) ? b : kNone;
    if (filling_ == kNone) dropped_.fetch_add(1, std::memory_order_relaxed);
  }
  if (filling_ == kNone) return;
  buffers_[filling_][j] = value;
  if (j + 1 == points_) {
    ready_.push(filling_);  // never full: kBuffers + 1 slots for kBuffers buffers
    filling_ = kNone;
  }
}

void RevolutionWelch::take_ready() {
  std::size_t b = 0;
  while (ready_.pop(b)) {
    try {
      transform(buffers_[b]);
    } catch (...) {
      if (!failure_) failure_ = std::current_exception();
    }
    free_.push(b);
  }
}

void RevolutionWelch::transform(const std::vector<double>& revolution) {
  const auto s =
      analyser_->analyse(revolution, static_cast<double>(points_), analysis::Window::kHann);
  power_.resize(s.amplitude.size(), 0.0);
  for (std::size_t i = 0; i < power_.size(); ++i) power_[i] += s.amplitude[i] * s.amplitude[i];
  resolution_ = s.resolution_hz;
  ++revolutions_;
}

RevolutionAverage RevolutionWelch::finish() {
  if (worker_.joinable()) {
    worker_.request_stop();
    worker_.join();
    take_ready();  // what came after the worker's last look
  }
  if (failure_) std::rethrow_exception(failure_);
  RevolutionAverage a;
  a.revolutions = revolutions_;
  // A revolution left unfinished at the end is not a drop.
  a.dropped = dropped_.load(std::memory_order_relaxed);
  if (a.dropped > 0 && index_ % points_ != 0 && filling_ == kNone) --a.dropped;
  a.resolution = resolution_;
  a.amplitude.reserve(power_.size());
  for (const double p : power_)
    a.amplitude.push_back(std::sqrt(p / static_cast<double>(revolutions_)));
  return a;
}

}  // namespace wavebench::metrology
