#include "wavebench/analysis/motion_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace wavebench::analysis {
namespace {

double distance(const PhasePoint& a, const PhasePoint& b) {
  return std::hypot(a.x - b.x, a.v - b.v);
}

// Smallest p with label[i] == label[i + p] for nearly all i: the period in strobe periods.
int repeat_period(const std::vector<int>& labels, int max_period) {
  const int n = static_cast<int>(labels.size());
  for (int p = 1; p <= max_period && 2 * p < n; ++p) {
    int same = 0;
    for (int i = 0; i + p < n; ++i)
      same += labels[static_cast<std::size_t>(i)] == labels[static_cast<std::size_t>(i + p)];
    if (same >= static_cast<int>(0.95 * (n - p))) return p;
  }
  return 0;
}

// Smallest p with |x_i - x_{i+p}| <= tolerance for nearly all i: a long period (commensurate
// lines) that the cluster count alone would take for a quasi-periodic or chaotic set.
// Returns closer than this (of the attractor size) are exact repeats, not slow drift.
constexpr double kExactRepeat = 1e-4;

int repeat_distance_period(std::span<const PhasePoint> p, double tolerance) {
  const int n = static_cast<int>(p.size());
  for (int k = 1; 2 * k <= n; ++k) {
    int same = 0;
    for (int i = 0; i + k < n; ++i) {
      same +=
          distance(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(i + k)]) <= tolerance;
    }
    if (same >= static_cast<int>(0.95 * (n - k))) return k;
  }
  return 0;
}

}  // namespace

const char* motion_class_name(MotionClass motion) {
  switch (motion) {
    case MotionClass::kPeriod1:
      return "period-1";
    case MotionClass::kPeriodN:
      return "period-n";
    case MotionClass::kQuasiPeriodic:
      return "quasi-periodic";
    case MotionClass::kChaotic:
      return "chaotic";
    case MotionClass::kUndetermined:
      break;
  }
  return "undetermined";
}

std::vector<int> cluster_points(std::span<const PhasePoint> p, double tolerance,
                                int* cluster_count) {
  // Leader clustering: a point joins the nearest cluster whose first point lies within the
  // tolerance, else it starts a new one. Unlike single linkage it does not chain the dense
  // points of a closed curve into one cluster, so a curve of length L counts about L / tol.
  std::vector<int> labels(p.size());
  std::vector<PhasePoint> leaders;
  for (std::size_t i = 0; i < p.size(); ++i) {
    int best = -1;
    double best_d = tolerance;
    for (std::size_t c = 0; c < leaders.size(); ++c) {
      const double d = distance(p[i], leaders[c]);
      if (d <= best_d) {
        best_d = d;
        best = static_cast<int>(c);
      }
    }
    if (best < 0) {
      best = static_cast<int>(leaders.size());
      leaders.push_back(p[i]);
    }
    labels[i] = best;
  }
  if (cluster_count) *cluster_count = static_cast<int>(leaders.size());
  return labels;
}

double correlation_dimension(std::span<const PhasePoint> all) {
  // Grassberger-Procaccia: slope of log C(r) between the radii that hold 0.5 % and 5 % of all
  // pairs, small enough to see the local structure, large enough to have statistics.
  // The pairs grow with the square of the points (100 000 points: 40 GB), so a long record's
  // section is thinned evenly to kMaxPoints (8 million pairs, 64 MB).
  constexpr std::size_t kMaxPoints = 4000;
  std::vector<PhasePoint> thinned;
  if (all.size() > kMaxPoints) {
    thinned.reserve(kMaxPoints);
    for (std::size_t k = 0; k < kMaxPoints; ++k)
      thinned.push_back(all[k * all.size() / kMaxPoints]);
  }
  const std::span<const PhasePoint> p =
      thinned.empty() ? all : std::span<const PhasePoint>(thinned);
  std::vector<double> d;
  d.reserve(p.size() * (p.size() - 1) / 2);
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) d.push_back(distance(p[i], p[j]));
  }
  if (d.size() < 100) return 0;
  const auto at = [&](double fraction) {
    const auto k = static_cast<std::size_t>(fraction * static_cast<double>(d.size()));
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
    return d[k];
  };
  const double r1 = at(0.005);
  const double r2 = at(0.05);
  if (!(r1 > 0) || !(r2 > r1)) return 0;
  return std::log(0.05 / 0.005) / std::log(r2 / r1);
}

double largest_lyapunov(std::span<const PhasePoint> p) {
  // Rosenstein: follow each point and its nearest neighbour for a few strobe periods; the mean
  // log separation grows with the largest exponent (per period).
  constexpr int kHorizon = 4;
  constexpr double kNoiseFloor = 1e-7;  // of the attractor size
  const int n = static_cast<int>(p.size());
  if (n < 4 * kHorizon) return 0;
  std::vector<double> mean_log(kHorizon + 1, 0.0);
  std::vector<int> counts(kHorizon + 1, 0);
  for (int i = 0; i + kHorizon < n; ++i) {
    int best = -1;
    double best_d = 1e300;
    for (int j = 0; j + kHorizon < n; ++j) {
      if (j == i) continue;
      const double dij = distance(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)]);
      // Closer than the integration noise: the orbit repeats; such a pair measures the
      // solver's round-off, not the dynamics.
      if (dij > kNoiseFloor && dij < best_d) {
        best_d = dij;
        best = j;
      }
    }
    if (best < 0) continue;
    for (int k = 0; k <= kHorizon; ++k) {
      const double dk =
          distance(p[static_cast<std::size_t>(i + k)], p[static_cast<std::size_t>(best + k)]);
      if (dk > 0) {
        mean_log[static_cast<std::size_t>(k)] += std::log(dk);
        ++counts[static_cast<std::size_t>(k)];
      }
    }
  }
  double sk = 0, sy = 0, skk = 0, sky = 0;
  int m = 0;
  for (int k = 0; k <= kHorizon; ++k) {
    if (counts[static_cast<std::size_t>(k)] == 0) continue;
    const double y = mean_log[static_cast<std::size_t>(k)] / counts[static_cast<std::size_t>(k)];
    sk += k;
    sy += y;
    skk += k * k;
    sky += k * y;
    ++m;
  }
  const double den = m * skk - sk * sk;
  return den > 0 ? (m * sky - sk * sy) / den : 0;
}

MotionClassification classify_motion(std::span<const PhasePoint> section,
                                     std::span<const PhasePoint> attractor,
                                     const MotionClassifierOptions& options) {
  MotionClassification result;
  auto& ev = result.evidence;
  ev.points = static_cast<int>(section.size());
  ev.cluster_tolerance = options.cluster_tolerance;
  if (section.size() < 8) {
    result.summary = "too few Poincare points (" + std::to_string(section.size()) +
                     ") to classify; record more excitation periods";
    return result;
  }
  // The attractor's extent sets the scale, so the tolerance means the same at any amplitude.
  const auto extent = [](std::span<const PhasePoint> pts, bool velocity) {
    double lo = 1e300, hi = -1e300;
    for (const auto& q : pts) {
      const double value = velocity ? q.v : q.x;
      lo = std::min(lo, value);
      hi = std::max(hi, value);
    }
    return hi - lo;
  };
  const auto reference = attractor.empty() ? section : attractor;
  double sx = extent(reference, false);
  double sv = extent(reference, true);
  if (!(sx > 0)) sx = 1;
  if (!(sv > 0)) sv = 1;
  std::vector<PhasePoint> p;
  p.reserve(section.size());
  for (const auto& q : section) p.push_back({q.x / sx, q.v / sv});

  const auto labels = cluster_points(p, options.cluster_tolerance, &ev.clusters);
  // Spread: the largest distance of a point from its cluster's centroid.
  std::vector<PhasePoint> centroid(static_cast<std::size_t>(ev.clusters));
  std::vector<int> members(static_cast<std::size_t>(ev.clusters), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    auto& c = centroid[static_cast<std::size_t>(labels[i])];
    c.x += p[i].x;
    c.v += p[i].v;
    ++members[static_cast<std::size_t>(labels[i])];
  }
  for (std::size_t c = 0; c < centroid.size(); ++c) {
    centroid[c].x /= members[c];
    centroid[c].v /= members[c];
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    ev.spread = std::max(ev.spread, distance(p[i], centroid[static_cast<std::size_t>(labels[i])]));
  }
  ev.correlation_dimension = correlation_dimension(p);

  std::ostringstream why;
  if (ev.clusters <= options.max_clusters) {
    // A period-n orbit visits exactly n clusters, one per strobe; points drifting slowly along
    // a curve also repeat their label from one strobe to the next, but over many clusters.
    ev.period = repeat_period(labels, options.max_clusters);
    if (ev.period != ev.clusters) ev.period = 0;
  }
  if (ev.period == 1 || ev.clusters == 1) {
    ev.period = 1;
    result.motion = MotionClass::kPeriod1;
    why << "period-1: all " << ev.points << " Poincare points in one cluster (spread " << ev.spread
        << " of the attractor size, tolerance " << options.cluster_tolerance << ")";
  } else if (ev.period > 1) {
    result.motion = MotionClass::kPeriodN;
    why << "period-" << ev.period << ": " << ev.clusters << " clusters visited in a cycle of "
        << ev.period << " strobe periods (spread " << ev.spread << ")";
  } else if (const int repeat = repeat_distance_period(p, kExactRepeat); repeat > 0) {
    // More clusters than a period-n orbit may have, but the sequence repeats exactly: lines at
    // commensurate frequencies (a closed curve visited in a fixed order).
    ev.period = repeat;
    result.motion = MotionClass::kQuasiPeriodic;
    why << "quasi-periodic: " << ev.clusters << " clusters on a closed curve (correlation "
        << "dimension " << ev.correlation_dimension << "), the sequence repeats after " << repeat
        << " strobe periods (commensurate lines)";
  } else {
    ev.lyapunov_per_period = largest_lyapunov(p);
    // D2 needs a few hundred points to mean anything; a contracting section is a transient
    // still settling onto its attractor, not an attractor to classify.
    const bool enough_for_dimension = ev.points >= 200;
    if (ev.lyapunov_per_period < -options.chaotic_lyapunov) {
      result.motion = MotionClass::kUndetermined;
      why << "undetermined: the section still contracts (largest Lyapunov exponent "
          << ev.lyapunov_per_period << " per strobe period, " << ev.clusters << " clusters in "
          << ev.points << " points): the transient is not over; record longer";
    } else {
      const bool chaotic =
          ev.lyapunov_per_period > options.chaotic_lyapunov ||
          (enough_for_dimension && ev.correlation_dimension > options.chaotic_dimension);
      result.motion = chaotic ? MotionClass::kChaotic : MotionClass::kQuasiPeriodic;
      why << (chaotic ? "chaotic: " : "quasi-periodic: ") << ev.clusters << " clusters in "
          << ev.points << " points, correlation dimension " << ev.correlation_dimension
          << ", largest Lyapunov exponent " << ev.lyapunov_per_period << " per strobe period"
          << (chaotic ? " (neighbours diverge / points fill an area)"
                      : " (points on a closed curve, neighbours stay close)");
    }
  }
  result.summary = why.str();
  return result;
}

}  // namespace wavebench::analysis
