#include "wavebench/bench/cycle_engine.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "wavebench/bench/bench.hpp"

namespace wavebench::bench {
namespace {

// Bits on the wire of a classic frame with `len` data bytes, with a typical stuffing allowance.
double frame_bits(unsigned len) {
  return (47.0 + 8.0 * len) * 1.2;
}

}  // namespace

CycleEngine::CycleEngine(canopen::Master& master, CycleClock& clock)
    : master_(master), clock_(clock) {}

void CycleEngine::attach(std::vector<CanopenDevice*> canopen_devices,
                         std::vector<BenchDevice*> others) {
  canopen_ = std::move(canopen_devices);
  others_ = std::move(others);
  sources_.clear();
  std::vector<std::pair<std::uint32_t, std::size_t>> cob_ids;
  for (auto* device : canopen_) {
    const auto tpdos = device->tpdos();
    for (std::size_t j = 0; j < tpdos.size(); ++j) {
      if (sources_.size() >= 32)
        throw std::invalid_argument("more than 32 TPDOs per cycle: " + device->describe());
      sources_.push_back({device, j, 1U << sources_.size()});
      cob_ids.emplace_back(tpdos[j].cob_id, sources_.size() - 1);
    }
  }
  expected_ = sources_.empty() ? 0 : static_cast<std::uint32_t>((1ULL << sources_.size()) - 1);
  // Indices, not pointers: sources_ is final here, but a handler outliving it must not dangle.
  for (const auto& entry : cob_ids) {
    const std::size_t i = entry.second;  // a copy: clang 14 cannot capture a structured binding
    master_.on_pdo(entry.first, [this, i](const can::Frame& f) {
      if (i < sources_.size()) on_frame(sources_[i], f);
    });
  }
}

void CycleEngine::start(CycleCheck check) {
  check_ = std::move(check);
  stats_ = {};
  lateness_ = {};
  open_ = false;
  running_ = true;
  mute_ = 0;
  late_devices_.clear();
  last_warning_ = {};
  clock_.on_late_answers({[this] { return awaits_answers(); },
                          [this] {
                            mute_ |= expected_ & ~arrived_;
                            awaited_ = 0;
                          }});
  clock_.start([this](std::uint64_t index, std::int64_t time_ns) { on_sync(index, time_ns); });
}

void CycleEngine::stop() noexcept {
  running_ = false;
  open_ = false;
  clock_.stop();
}

void CycleEngine::add_observer(SampleObserver& observer) {
  if (std::find(observers_.begin(), observers_.end(), &observer) == observers_.end())
    observers_.push_back(&observer);
}

void CycleEngine::remove_observer(SampleObserver& observer) {
  std::erase(observers_, &observer);
}

void CycleEngine::on_sync(std::uint64_t index, std::int64_t time_ns) {
  if (!running_) return;
  close();
  ++stats_.syncs_sent;
  auto& s = record_.sample;
  s.sync_counter = static_cast<std::uint32_t>(index % 240 + 1);
  s.flags = 0;
  s.receive_time_ns = time_ns;
  s.missed_before = 0;
  s.extra_valid = 0;
  record_.drive.status_valid = false;
  record_.drive.following_error_valid = false;
  arrived_ = 0;
  awaited_ = 0;
  open_ = true;
  for (auto* device : canopen_) device->on_sync(index);
}

bool CycleEngine::awaits_answers() noexcept {
  const std::uint32_t missing = expected_ & ~arrived_ & ~mute_;
  if (!open_ || missing == 0) return false;
  awaited_ = missing;  // named as late once their answers are in
  return true;
}

void CycleEngine::note_late(std::uint32_t missing) noexcept {
  bool added = false;
  for (const auto& source : sources_) {
    if ((missing & source.bit) == 0) continue;
    const auto name = source.device->describe();
    if (std::find(late_devices_.begin(), late_devices_.end(), name) != late_devices_.end())
      continue;
    late_devices_.push_back(name);
    added = true;
  }
  // One warning per start, another only for a newly late device and at most once a minute.
  const auto now = std::chrono::steady_clock::now();
  if (!added || (last_warning_ != std::chrono::steady_clock::time_point{} &&
                 now - last_warning_ < std::chrono::minutes(1)))
    return;
  last_warning_ = now;
  std::string names;
  for (const auto& n : late_devices_) names += (names.empty() ? "" : ", ") + n;
  spdlog::warn(
      "slower than the SYNC rate: {}; the simulated clock waited for their answers before the "
      "next SYNC (acquisition_stats: cycles_waited_for_devices)",
      names);
}

void CycleEngine::on_frame(const FrameSource& source, const can::Frame& frame) noexcept {
  mute_ &= ~source.bit;  // it speaks: waited for again
  if (!open_ || !clock_.received_after_sync(frame) || (arrived_ & source.bit) != 0 ||
      !source.device->on_pdo(source.tpdo, frame, record_)) {
    ++stats_.late_frames;
    return;
  }
  arrived_ |= source.bit;
  if (arrived_ == expected_) {
    if (awaited_ != 0) note_late(awaited_);
    awaited_ = 0;
    close();
    clock_.cycle_complete();
  }
}

void CycleEngine::close() noexcept {
  if (!open_) return;
  open_ = false;
  for (auto* device : others_) device->on_cycle_end(record_);
  latest_ = record_;
  ++stats_.samples;
  if (!latest_.sample.complete()) ++stats_.incomplete_samples;
  for (auto* observer : observers_) observer->on_sample(latest_.sample);
  if (check_) check_(latest_);
}

double CycleEngine::bits_per_cycle() const {
  double bits = frame_bits(0);  // SYNC
  for (auto* device : canopen_)
    for (const auto& pdo : device->tpdos()) {
      unsigned payload = 0;
      for (const auto& e : pdo.entries) payload += e.bits;
      bits += frame_bits((payload + 7) / 8);
    }
  return bits;
}

}  // namespace wavebench::bench
