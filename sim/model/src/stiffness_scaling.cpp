#include "wavebench/model/stiffness_scaling.hpp"

#include <stdexcept>
#include <string>
#include <variant>

namespace wavebench::model {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// Clang 14 (the fuzz build) has no aggregate class template argument deduction.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

void scale_stiffness(StiffnessParams& stiffness, double f) {
  if (!(f > 0))
    throw std::invalid_argument("stiffness scale " + std::to_string(f) + ": expected > 0");
  std::visit(Overloaded{[&](LinearPeriodicStiffness& l) {
                          l.k0 *= f;
                          for (auto& h : l.harmonics) h.amplitude *= f;
                        },
                        [&](CubicStiffness& c) {
                          c.k1 *= f;
                          c.k3 *= f;
                        },
                        [&](ThreeSegmentStiffness& c) {
                          c.k1 *= f;
                          c.k2 *= f;
                          c.k3 *= f;
                        },
                        [&](TableStiffness& t) {
                          for (double& v : t.torque_nm) v *= f;
                        },
                        [&](HystereticBranchStiffness& h) {
                          h.a_load *= f;
                          h.b_load *= f;
                          h.c_load *= f;
                          h.a_unload *= f;
                          h.b_unload *= f;
                          h.c_unload *= f;
                        },
                        [&](FadingMemoryStiffness& m) {
                          m.a *= f;
                          m.b *= f;
                          m.c *= f;
                          m.memory_gain *= f;
                        },
                        [&](BoucWenStiffness& b) { b.k *= f; }},
             stiffness.law);
  if (stiffness.mean_stiffness) *stiffness.mean_stiffness *= f;
}

}  // namespace wavebench::model
