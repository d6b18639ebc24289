// How much faster than real time the simulated bench runs: the servo loop with the plant alone
// (advance), and full SYNC cycles on the VirtualCanBus (SYNC in, 4 TPDOs out, delivered).
#include <benchmark/benchmark.h>

#include <boost/asio/io_context.hpp>

#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/config/shipped_configs.hpp"
#include "wavebench/config/twin_case.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace {

using wavebench::simdevices::BenchClock;
using wavebench::simdevices::SimulatedBench;
using wavebench::simdevices::SimulatedBenchConfig;

// The simulated devices' default unit, as `wavebench simbench` loads it.
const wavebench::model::GearParams& simulated_devices_gear() {
  static const auto gear =
      wavebench::config::load_twin_case(wavebench::config::shipped_config_dir() / "benches" /
                                        "simulated-devices-gear.yaml")
          .gear;
  return gear;
}

void enable_velocity_mode(SimulatedBench& bench) {
  auto& od = bench.drive().od();
  const std::uint8_t mode[] = {3};
  (void)od.write(0x6060, 0, mode);
  for (const std::uint16_t cw : {0x06, 0x07, 0x0F}) {
    const std::uint8_t b[] = {static_cast<std::uint8_t>(cw), 0};
    (void)od.write(0x6040, 0, b);
  }
  const std::int32_t v = 131072 * 100 / 60;  // 100 rpm at the input
  const std::uint8_t t[] = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                            static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
  (void)od.write(0x60FF, 0, t);
}

// One simulated second per iteration; the "x real time" counter is the figure of merit.
void BM_AdvanceOneSimulatedSecond(benchmark::State& state) {
  boost::asio::io_context io;
  wavebench::can::VirtualCanBus bus(io);
  auto ep = bus.endpoint("simbench");
  SimulatedBenchConfig config;
  config.gear = simulated_devices_gear();
  config.clock = BenchClock::kManual;
  SimulatedBench bench(config, *ep);
  bench.start();
  enable_velocity_mode(bench);
  for (auto _ : state) {
    bench.advance(1.0);
    io.poll();
    io.restart();
  }
  state.counters["x_real_time"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AdvanceOneSimulatedSecond)->Unit(benchmark::kMillisecond);

// SYNC-driven: 1000 SYNC cycles (one simulated second at 1 kHz) with every TPDO delivered.
void BM_ThousandSyncCycles(benchmark::State& state) {
  boost::asio::io_context io;
  wavebench::can::VirtualCanBus bus(io);
  bus.record(false);
  auto master = bus.endpoint("master");
  auto devices = bus.endpoint("simbench");
  SimulatedBenchConfig config;
  config.gear = simulated_devices_gear();
  config.clock = BenchClock::kSyncDriven;
  SimulatedBench bench(config, *devices);
  bench.start();
  enable_velocity_mode(bench);
  std::uint64_t pdos = 0;
  auto sub = master->on_frame([&](const wavebench::can::Frame& f) {
    if (f.id >= 0x180 && f.id < 0x500) ++pdos;
  });
  master->send(wavebench::can::Frame::make(0x000, {0x01, 0x00}));
  io.poll();
  io.restart();
  const auto sync = wavebench::can::Frame::make(0x080, std::initializer_list<std::uint8_t>{});
  for (auto _ : state) {
    for (int i = 0; i < 1000; ++i) {
      master->send(sync);
      io.poll();
      io.restart();
    }
  }
  state.counters["x_real_time"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["pdos_per_sync"] =
      static_cast<double>(pdos) / (1000.0 * static_cast<double>(state.iterations()));
}
BENCHMARK(BM_ThousandSyncCycles)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
