// Steps must not allocate: the XB-80 case takes ~1e5..1e6 steps and 2e5 samples per run.
// Counts calls of the global operator new (replaced for this test binary; the replacement only
// counts and forwards to malloc).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "test_problems.hpp"
#include "wavebench/model/solver/integrators.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Out of line, so GCC does not pair the malloc/free inside with new/delete at inlined call
// sites (-Wmismatched-new-delete).
[[gnu::noinline]] void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* p) noexcept {
  std::free(p);
}
[[gnu::noinline]] void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace wavebench::model::solver {
namespace {

class AllocationFreeSteps : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(AllocationFreeSteps, StepAndDenseOutputDoNotAllocate) {
  const testing::LinearOscillator system(6.0, 0.05, 3.0, 2.0);
  auto integrator = make_integrator(GetParam(), {1e-8, 1e-10}, 1e-3, 0);
  integrator->initialize(system, 0.0, std::vector<double>{1.0, 0.0}, {}, 0);
  std::vector<double> y(2);
  const long before = g_allocations.load();
  for (int i = 0; i < 200; ++i) {
    integrator->step(100.0);
    integrator->dense_output(0.5 * (integrator->previous_time() + integrator->current_time()), y);
  }
  integrator->reset(integrator->current_time(), y);
  integrator->step(100.0);
  EXPECT_EQ(g_allocations.load() - before, 0) << integrator->name();
}

TEST_P(AllocationFreeSteps, RunnerAllocatesOnlyInSetup) {
  // Allocations of a run must not grow with its length (run 0 warms the integrator's buffers).
  const testing::LinearOscillator system(6.0, 0.05, 3.0, 2.0);
  auto integrator = make_integrator(GetParam(), {1e-8, 1e-10}, 1e-3, 0);
  long counts[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    TrajectoryOptions options;
    options.t_end = 2.0 * (i + 1);
    options.sample_rate = 1000;
    TrajectoryRunner runner(*integrator, system, options);
    double sum = 0;
    runner.on_sample(
        [&sum](double, std::span<const double> yy, std::span<const double>) { sum += yy[0]; });
    std::vector<double> y{1.0, 0.0};
    const long before = g_allocations.load();
    const auto result = runner.run(0.0, y, {});
    counts[i] = g_allocations.load() - before;
    EXPECT_EQ(result.samples, 2000 * (i + 1) + 1);
    EXPECT_NE(sum, 0.0);
  }
  EXPECT_EQ(counts[1], counts[2]) << integrator->name();
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, AllocationFreeSteps,
                         ::testing::Values(IntegratorKind::kDormandPrince45, IntegratorKind::kRk4,
                                           IntegratorKind::kRosenbrock));

}  // namespace
}  // namespace wavebench::model::solver
