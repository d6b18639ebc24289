// Round trips of the brake client against the simulated controller over loopback TCP.
// Reports transactions per second (items_per_second) and latency percentiles per transaction.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "wavebench/modbus/brake_client.hpp"
#include "wavebench/simdevices/brake_server.hpp"

namespace {

using namespace wavebench;
using Clock = std::chrono::steady_clock;

struct Bench {
  Bench() {
    simdevices::BrakeServerOptions o;
    o.endpoint = modbus::parse_modbus_endpoint("tcp:127.0.0.1:0");
    server = simdevices::start_brake_server(o);
    modbus::BrakeClientConfig c;
    c.link.endpoint =
        modbus::parse_modbus_endpoint("tcp:127.0.0.1:" + std::to_string(server->port()));
    client = std::make_unique<modbus::BrakeClient>(c);
    client->connect();
  }
  std::unique_ptr<simdevices::BrakeServer> server;
  std::unique_ptr<modbus::BrakeClient> client;
};

template <typename Op>
void measure(benchmark::State& state, Op op) {
  Bench b;
  std::vector<double> latencies;
  latencies.reserve(1 << 16);
  const auto before = b.client->transactions();
  for (auto _ : state) {
    const auto t0 = Clock::now();
    op(*b.client);
    latencies.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  const auto transactions = b.client->transactions() - before;
  state.SetItemsProcessed(static_cast<int64_t>(transactions));
  std::sort(latencies.begin(), latencies.end());
  auto pct = [&](double p) {
    return latencies.empty() ? 0.0 : latencies[static_cast<size_t>(p * (latencies.size() - 1))];
  };
  state.counters["p50_us"] = pct(0.50);
  state.counters["p99_us"] = pct(0.99);
  state.counters["max_us"] = latencies.empty() ? 0.0 : latencies.back();
  state.counters["tx_per_op"] =
      static_cast<double>(transactions) / static_cast<double>(latencies.size());
}

// One read of input registers 0..20 (function 4): the readback poll.
void BM_BrakeReadback(benchmark::State& state) {
  measure(state, [](modbus::BrakeClient& c) { benchmark::DoNotOptimize(c.read()); });
}
// One write of the heartbeat register (function 6).
void BM_BrakeHeartbeat(benchmark::State& state) {
  measure(state, [](modbus::BrakeClient& c) { c.heartbeat(); });
}
// A supervisor cycle: heartbeat + readback.
void BM_BrakeSupervisorCycle(benchmark::State& state) {
  measure(state, [](modbus::BrakeClient& c) {
    c.heartbeat();
    benchmark::DoNotOptimize(c.read());
  });
}

BENCHMARK(BM_BrakeReadback)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_BrakeHeartbeat)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_BrakeSupervisorCycle)->MinTime(2.0)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
