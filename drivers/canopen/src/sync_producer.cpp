#include "wavebench/canopen/sync_producer.hpp"

#include <stdexcept>
#include <string>

#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::canopen {

can::Frame sync_frame(std::uint8_t counter) {
  if (counter == 0) return can::Frame::make(kSyncCobId, {});
  return can::Frame::make(kSyncCobId, {counter});
}

SyncProducer::SyncProducer(can::CanBus& bus, std::chrono::microseconds period,
                           std::uint8_t counter_overflow)
    : bus_(bus),
      period_(period),
      overflow_(counter_overflow),
      timer_(bus.context()),
      late_threshold_(period / 2) {
  if (period.count() <= 0) {
    throw std::invalid_argument("SYNC period " + std::to_string(period.count()) +
                                " us (0x1006): expected > 0");
  }
  if (counter_overflow == 1 || counter_overflow > 240) {
    throw std::invalid_argument("SYNC counter overflow " + std::to_string(counter_overflow) +
                                " (0x1019): expected 0 (no counter) or 2..240");
  }
}

SyncProducer::~SyncProducer() {
  stop();
}

void SyncProducer::start() {
  if (running_) return;
  running_ = true;
  counter_ = 0;
  k_ = 0;
  t0_ = Clock::now();
  schedule();
}

void SyncProducer::stop() noexcept {
  running_ = false;
  timer_.cancel();
}

void SyncProducer::schedule() noexcept {
  timer_.expires_at(t0_ + static_cast<std::int64_t>(k_) * period_);
  timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec == boost::asio::error::operation_aborted || !running_) return;
    fire();
  });
}

void SyncProducer::fire() noexcept {
  const auto deadline = t0_ + static_cast<std::int64_t>(k_) * period_;
  if (overflow_ != 0) counter_ = static_cast<std::uint8_t>(counter_ % overflow_ + 1);
  std::error_code ec;
  bus_.send(sync_frame(counter_), ec);
  const auto now = Clock::now();
  Tick tick{k_, counter_, deadline, now, !ec};
  ++stats_.sent;
  if (ec) ++stats_.send_errors;
  const auto lateness = now - deadline;
  if (lateness > stats_.max_lateness) stats_.max_lateness = lateness;
  if (lateness > late_threshold_) {
    ++stats_.late;
    if (on_late_) on_late_(tick, lateness);
  }
  if (on_tick_) on_tick_(tick);
  if (!running_) return;  // a hook may stop the producer
  ++k_;
  // Skip deadlines already in the past: one SYNC per wakeup, phase kept.
  const auto behind = (Clock::now() - (t0_ + static_cast<std::int64_t>(k_) * period_)) / period_;
  if (behind > 0) {
    stats_.skipped += static_cast<std::uint64_t>(behind);
    k_ += static_cast<std::uint64_t>(behind);
  }
  schedule();
}

}  // namespace wavebench::canopen
