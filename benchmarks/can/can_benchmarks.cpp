// Decoded frames/s through the in-process bus and SDO round trips/s against an in-process server.
#include <benchmark/benchmark.h>

#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/canopen/frame_description.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wc = wavebench::can;
namespace co = wavebench::canopen;

namespace {

// A TPDO stream (statusword, position, torque) sent and decoded by a subscriber.
void DecodedPdoFrames(benchmark::State& state) {
  boost::asio::io_context io;
  wc::VirtualCanBus bus(io);
  bus.record(false);
  auto tx = bus.endpoint();
  auto rx = bus.endpoint();
  const co::PdoLayout layout({{0x6041, 0, 16}, {0x6064, 0, 32}, {0x6077, 0, 16}});
  std::int64_t sum = 0;
  std::uint64_t decoded = 0;
  auto sub = rx->on_frame([&](const wc::Frame& f) {
    if (f.id == 0x181 && layout.fits(f)) {
      sum += layout.signed_value(f, 1) + layout.signed_value(f, 2);
      ++decoded;
    }
  });
  const std::uint64_t values[] = {0x0637, 123456, 0xFF38};
  const auto frame = layout.make_frame(0x181, values);
  for (auto _ : state) {
    for (int i = 0; i < 1000; ++i) tx->send(frame);
    io.restart();
    io.run();
  }
  benchmark::DoNotOptimize(sum);
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(decoded), benchmark::Counter::kIsRate);
}
BENCHMARK(DecodedPdoFrames)->Unit(benchmark::kMillisecond);

// The dump path: every frame decoded into text.
void DescribedFrames(benchmark::State& state) {
  const wc::Frame frames[] = {*wc::parse_frame("181#3706401E0100C800"), *wc::parse_frame("080#"),
                              *wc::parse_frame("581#4318100178563412"), *wc::parse_frame("701#05"),
                              *wc::parse_frame("081#1023010000000000")};
  std::size_t chars = 0;
  std::uint64_t n = 0;
  for (auto _ : state) {
    for (const auto& f : frames) {
      chars += co::describe_frame(f).size();
      ++n;
    }
  }
  benchmark::DoNotOptimize(chars);
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate);
}
BENCHMARK(DescribedFrames);

// Expedited SDO uploads, each waiting for its reply, against a server endpoint that answers
// every request at once.
void SdoRoundTrips(benchmark::State& state) {
  boost::asio::io_context io;
  wc::VirtualCanBus bus(io);
  bus.record(false);
  auto master = bus.endpoint();
  auto server = bus.endpoint();
  auto sub = server->on_frame([&](const wc::Frame& f) {
    if (f.id != 0x601 || f.len != 8 || f.data[0] != 0x40) return;
    auto reply = wc::Frame::make(0x581, {0x43, f.data[1], f.data[2], f.data[3], 1, 2, 3, 4});
    server->send(reply);
  });
  co::SdoClient sdo(*master, 1, std::chrono::milliseconds(1000));
  std::uint64_t trips = 0;
  for (auto _ : state) {
    int remaining = 1000;
    std::function<void(std::error_code, std::vector<std::uint8_t>)> next;
    next = [&](std::error_code ec, std::vector<std::uint8_t>) {
      if (!ec) ++trips;
      if (--remaining > 0) sdo.async_upload(0x1018, 1, next);
    };
    sdo.async_upload(0x1018, 1, next);
    io.restart();
    while (remaining > 0) io.run_one();
  }
  state.counters["round trips/s"] =
      benchmark::Counter(static_cast<double>(trips), benchmark::Counter::kIsRate);
}
BENCHMARK(SdoRoundTrips)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
