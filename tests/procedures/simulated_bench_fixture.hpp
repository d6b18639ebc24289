#pragma once
// The in-process simulated bench as the shipped sim.yaml builds it, connected for the test's
// lifetime, with the simulator's access for its truth.

#include <memory>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"

namespace wavebench::procedures::testing {

struct Sim {
  Sim() : bench(bench::make_simulated_bench(bench::default_simulated_bench_config())) {
    access = bench::simulated_access(*bench);
    bench->connect();
  }
  ~Sim() { bench->disconnect(); }
  std::unique_ptr<bench::Bench> bench;
  bench::SimulatedBenchAccess* access = nullptr;
};

}  // namespace wavebench::procedures::testing
