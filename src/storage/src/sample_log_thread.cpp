#include "wavebench/storage/sample_log_thread.hpp"

#include <array>
#include <exception>
#include <system_error>
#include <type_traits>

namespace wavebench::storage {

static_assert(std::is_trivially_copyable_v<SyncSample>,
              "the acquisition thread copies samples into the queue without allocating");

SampleLogThread::SampleLogThread(SampleLogWriter& writer, FailureSink on_failure,
                                 SampleLogThreadOptions options)
    : writer_(writer),
      on_failure_(std::move(on_failure)),
      options_(options),
      queue_(options.queue_capacity) {
  thread_ = std::thread([this] { run(); });
}

SampleLogThread::~SampleLogThread() {
  finish();
}

bool SampleLogThread::try_push(const SyncSample& sample) noexcept {
  pushed_.fetch_add(1, std::memory_order_relaxed);
  if (options_.lockstep_backlog > 0) {
    // The writer thread drains whatever it finds, failed or not: this wait always ends.
    while (options_.queue_capacity - queue_.write_available() > options_.lockstep_backlog) {
      std::this_thread::yield();
    }
  }
  if (queue_.push(sample)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

void SampleLogThread::finish() {
  if (finished_) return;
  finished_ = true;
  stopping_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

void SampleLogThread::run() noexcept {
  constexpr std::size_t kBatch = 256;
  std::array<SyncSample, kBatch> batch;
  for (;;) {
    const std::size_t n = queue_.pop(batch.data(), batch.size());
    if (n > 0) {
      write_batch(batch.data(), n);
      continue;
    }
    // Everything pushed before stopping_ was raised is visible now: one more empty look ends.
    if (stopping_.load(std::memory_order_acquire)) {
      if (queue_.read_available() == 0) break;
      continue;
    }
    flush_if_due();  // a stalled bus must not leave samples buffered
    std::this_thread::sleep_for(options_.poll_interval);
  }
  flush_if_due();
}

void SampleLogThread::write_batch(const SyncSample* samples, std::size_t count) noexcept {
  for (std::size_t i = 0; i < count; ++i) {
    if (failed_) {
      not_written_.fetch_add(count - i, std::memory_order_relaxed);
      return;
    }
    try {
      writer_.append(samples[i]);
    } catch (const std::system_error& e) {
      not_written_.fetch_add(1, std::memory_order_relaxed);
      fail(e.code().value(), e.what());
    } catch (const std::exception& e) {
      not_written_.fetch_add(1, std::memory_order_relaxed);
      fail(0, e.what());
    }
  }
  flush_if_due();
}

void SampleLogThread::flush_if_due() noexcept {
  if (failed_) return;
  try {
    writer_.flush_if_due();
  } catch (const std::system_error& e) {
    fail(e.code().value(), e.what());
  } catch (const std::exception& e) {
    fail(0, e.what());
  }
}

void SampleLogThread::fail(int error, const std::string& what) noexcept {
  failed_ = true;
  if (!on_failure_) return;
  try {
    on_failure_(error, what);
  } catch (...) {  // NOLINT(bugprone-empty-catch): the sink reports; it must not end the thread
  }
}

}  // namespace wavebench::storage
