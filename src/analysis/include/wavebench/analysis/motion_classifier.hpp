#pragma once
// Classifying the motion from its Poincare section (model.md §9).

#include <span>
#include <string>
#include <vector>

#include "wavebench/analysis/poincare_section.hpp"

namespace wavebench::analysis {

enum class MotionClass { kPeriod1, kPeriodN, kQuasiPeriodic, kChaotic, kUndetermined };

struct MotionEvidence {
  int clusters = 0;  // clusters of section points within the tolerance
  int period = 0;    // n for period-n; for a quasi-periodic set whose strobe sequence repeats
                     // (commensurate lines), the repeat length
  double cluster_tolerance = 0;      // relative to the attractor size
  double spread = 0;                 // largest cluster radius / attractor size
  double correlation_dimension = 0;  // Grassberger-Procaccia D2 of the section points
  double lyapunov_per_period = 0;    // largest exponent from neighbour divergence (Rosenstein)
  int points = 0;
};

struct MotionClassification {
  MotionClass motion = MotionClass::kUndetermined;
  MotionEvidence evidence;
  std::string summary;  // one sentence with the numbers
};

struct MotionClassifierOptions {
  int max_clusters = 16;
  double cluster_tolerance = 0.01;  // of the attractor size
  double chaotic_lyapunov = 0.1;    // per strobe period, above = chaotic
  double chaotic_dimension = 1.35;  // D2 above = chaotic even if neighbours diverge slowly
};

// `attractor` is the whole trajectory (the phase portrait): its extent normalises the section.
MotionClassification classify_motion(std::span<const PhasePoint> section,
                                     std::span<const PhasePoint> attractor,
                                     const MotionClassifierOptions& options);

const char* motion_class_name(MotionClass motion);  // "period-1", "period-n", ...

// Pieces, exposed for tests.
std::vector<int> cluster_points(std::span<const PhasePoint> normalised, double tolerance,
                                int* cluster_count);
double correlation_dimension(std::span<const PhasePoint> normalised);
double largest_lyapunov(std::span<const PhasePoint> normalised);

}  // namespace wavebench::analysis
