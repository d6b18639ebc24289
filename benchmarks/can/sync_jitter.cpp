// SYNC producer period jitter on this host: 1 kHz (or --period-us) for 60 s (or --seconds) on
// the in-process bus; prints wakeup lateness p50/p99/max and the period p50/p99/max deviation.
// Usage: sync_jitter [seconds=60] [period_us=1000]
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/canopen/sync_producer.hpp"

namespace wc = wavebench::can;
namespace co = wavebench::canopen;
using Clock = co::SyncProducer::Clock;

namespace {

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 60.0;
  const long period_us = argc > 2 ? std::atol(argv[2]) : 1000;
  if (seconds <= 0 || period_us <= 0) {
    fmt::print(stderr, "usage: sync_jitter [seconds>0] [period_us>0]\n");
    return 2;
  }
  boost::asio::io_context io;
  wc::VirtualCanBus bus(io);
  bus.record(false);
  auto tx = bus.endpoint();
  auto rx = bus.endpoint();
  std::uint64_t received = 0;
  auto sub = rx->on_frame([&](const wc::Frame&) { ++received; });
  co::SyncProducer sync(*tx, std::chrono::microseconds(period_us));
  const auto total = static_cast<std::size_t>(seconds * 1e6 / static_cast<double>(period_us));
  std::vector<double> lateness_us;
  std::vector<double> period_error_us;
  lateness_us.reserve(total);
  period_error_us.reserve(total);
  Clock::time_point previous{};
  sync.on_tick([&](const co::SyncProducer::Tick& t) {
    lateness_us.push_back(std::chrono::duration<double, std::micro>(t.sent - t.deadline).count());
    if (previous != Clock::time_point{}) {
      period_error_us.push_back(
          std::chrono::duration<double, std::micro>(t.sent - previous).count() -
          static_cast<double>(period_us));
    }
    previous = t.sent;
    if (lateness_us.size() >= total) sync.stop();
  });
  sync.start();
  io.run();
  const auto& st = sync.statistics();
  std::vector<double> abs_err(period_error_us.size());
  std::transform(period_error_us.begin(), period_error_us.end(), abs_err.begin(),
                 [](double e) { return e < 0 ? -e : e; });
  fmt::print("SYNC {} us for {} s: {} sent, {} received, {} late (> period/2), {} skipped\n",
             period_us, seconds, st.sent, received, st.late, st.skipped);
  fmt::print("wakeup lateness  p50 {:.1f} us  p99 {:.1f} us  max {:.1f} us\n",
             percentile(lateness_us, 0.50), percentile(lateness_us, 0.99),
             percentile(lateness_us, 1.0));
  fmt::print("|period - {} us| p50 {:.1f} us  p99 {:.1f} us  max {:.1f} us\n", period_us,
             percentile(abs_err, 0.50), percentile(abs_err, 0.99), percentile(abs_err, 1.0));
  return 0;
}
