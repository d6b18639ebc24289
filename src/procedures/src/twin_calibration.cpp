#include "wavebench/procedures/twin_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "wavebench/procedures/dynamic_te_analysis.hpp"

namespace wavebench::procedures {

TwinResidual twin_residual(std::span<const double> time_s, std::span<const double> measured_te_rad,
                           std::span<const double> predicted_te_rad, analysis::Window window,
                           analysis::SpectrumAnalyser& analyser) {
  const std::size_t n = time_s.size();
  if (measured_te_rad.size() != n || predicted_te_rad.size() != n || n < 8) {
    throw std::invalid_argument("twin residual: time has " + std::to_string(n) +
                                " samples, measured " + std::to_string(measured_te_rad.size()) +
                                ", predicted " + std::to_string(predicted_te_rad.size()) +
                                "; expected equal lengths of at least 8");
  }
  TwinResidual r;
  r.residual_arcsec.resize(n);
  double sum = 0, squares = 0, lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = (measured_te_rad[i] - predicted_te_rad[i]) * kArcsecPerRad;
    r.residual_arcsec[i] = v;
    sum += v;
    squares += v * v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  r.mean_arcsec = sum / static_cast<double>(n);
  r.rms_arcsec = std::sqrt(squares / static_cast<double>(n));
  r.p2p_arcsec = hi - lo;
  r.spectrum_hz = spectrum_on_timestamps(time_s, r.residual_arcsec, window, analyser);
  return r;
}

double HarmonicFit::evaluate(double theta1, double theta2) const {
  double e = offset_rad;
  for (const auto& h : harmonics) {
    e += h.amplitude_rad * std::sin(h.order_input * theta1 + h.order_output * theta2 + h.phase_rad);
  }
  return e;
}

HarmonicFit fit_te_harmonics(std::span<const double> theta1_rad, std::span<const double> theta2_rad,
                             std::span<const double> te_rad,
                             std::span<const HarmonicOrder> orders) {
  return fit_te_harmonics(theta1_rad, theta2_rad, te_rad, orders, {}).fit;
}

HarmonicRegression fit_te_harmonics(std::span<const double> theta1_rad,
                                    std::span<const double> theta2_rad,
                                    std::span<const double> te_rad,
                                    std::span<const HarmonicOrder> orders,
                                    std::span<const std::vector<double>> regressors) {
  const std::size_t n = te_rad.size();
  const std::size_t harmonic_unknowns = 1 + 2 * orders.size();
  const std::size_t unknowns = harmonic_unknowns + regressors.size();
  for (std::size_t r = 0; r < regressors.size(); ++r) {
    if (regressors[r].size() != n) {
      throw std::invalid_argument("TE harmonic fit: regressor " + std::to_string(r) + " has " +
                                  std::to_string(regressors[r].size()) +
                                  " values; expected one per TE sample (" + std::to_string(n) +
                                  ")");
    }
  }
  if (theta1_rad.size() != n || theta2_rad.size() != n || n < unknowns) {
    throw std::invalid_argument("TE harmonic fit: " + std::to_string(n) + " TE samples, θ1 " +
                                std::to_string(theta1_rad.size()) + ", θ2 " +
                                std::to_string(theta2_rad.size()) +
                                "; expected equal lengths >= " + std::to_string(unknowns));
  }
  for (std::size_t i = 0; i < orders.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (orders[i].order_input == orders[j].order_input &&
          orders[i].order_output == orders[j].order_output) {
        throw std::invalid_argument(
            "TE harmonic fit: order (" + std::to_string(orders[i].order_input) + ", " +
            std::to_string(orders[i].order_output) + ") of '" + orders[i].name + "' repeats '" +
            orders[j].name + "'; expected distinct orders");
      }
    }
  }
  const auto rows = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd a(rows, static_cast<Eigen::Index>(unknowns));
  Eigen::VectorXd b(rows);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const auto k = static_cast<std::size_t>(i);
    a(i, 0) = 1.0;
    for (std::size_t j = 0; j < orders.size(); ++j) {
      const double x =
          orders[j].order_input * theta1_rad[k] + orders[j].order_output * theta2_rad[k];
      a(i, static_cast<Eigen::Index>(1 + 2 * j)) = std::sin(x);
      a(i, static_cast<Eigen::Index>(2 + 2 * j)) = std::cos(x);
    }
    for (std::size_t r = 0; r < regressors.size(); ++r) {
      a(i, static_cast<Eigen::Index>(harmonic_unknowns + r)) = regressors[r][k];
    }
    b(i) = te_rad[k];
  }
  const Eigen::VectorXd x = a.colPivHouseholderQr().solve(b);
  HarmonicFit fit;
  fit.offset_rad = x(0);
  for (std::size_t j = 0; j < orders.size(); ++j) {
    // A·sin(u + φ) = A·cos φ·sin u + A·sin φ·cos u
    const double s = x(static_cast<Eigen::Index>(1 + 2 * j));
    const double c = x(static_cast<Eigen::Index>(2 + 2 * j));
    fit.harmonics.push_back({orders[j].name, orders[j].order_input, orders[j].order_output,
                             std::hypot(s, c), std::atan2(c, s)});
  }
  fit.rms_residual_rad = std::sqrt((a * x - b).squaredNorm() / static_cast<double>(n));
  HarmonicRegression out{std::move(fit), {}};
  for (std::size_t r = 0; r < regressors.size(); ++r) {
    out.coefficients.push_back(x(static_cast<Eigen::Index>(harmonic_unknowns + r)));
  }
  return out;
}

StiffnessBacklashEstimate estimate_stiffness_backlash(const StaticTeResult& run) {
  if (run.lost_motion.empty() || run.load_shifts.empty()) {
    throw std::invalid_argument("stiffness/backlash estimate: the static run has " +
                                std::to_string(run.lost_motion.size()) +
                                " forward/reverse pairs and " +
                                std::to_string(run.load_shifts.size()) +
                                " load shifts; expected both directions at two loads at least");
  }
  const auto lowest = std::min_element(
      run.lost_motion.begin(), run.lost_motion.end(),
      [](const LostMotionProfile& x, const LostMotionProfile& y) { return x.load_nm < y.load_nm; });
  StiffnessBacklashEstimate e;
  e.backlash_rad = lowest->mean_arcmin / kArcminPerRad;
  double top = -INFINITY;
  for (const auto& s : run.load_shifts) top = std::max(top, s.load_nm);
  double shift = 0;
  int count = 0;
  for (const auto& s : run.load_shifts) {
    if (s.load_nm != top) continue;
    // The directions shift opposite ways (the twist follows the torque, which follows the
    // direction of travel): their magnitudes are the twist.
    shift += std::abs(s.shift_arcmin) / kArcminPerRad;
    e.load_nm = s.load_nm - s.reference_load_nm;
    ++count;
  }
  e.shift_rad = shift / count;
  if (e.shift_rad == 0) {
    throw std::invalid_argument("stiffness/backlash estimate: mean TE shift under " +
                                std::to_string(e.load_nm) + " N·m is 0; expected a twist");
  }
  e.stiffness_nm_per_rad = e.load_nm / e.shift_rad;
  return e;
}

nlohmann::json to_json(const HarmonicFit& fit) {
  nlohmann::json terms = nlohmann::json::array();
  for (const auto& h : fit.harmonics) {
    terms.push_back({{"source", h.name},
                     {"order_input", h.order_input},
                     {"order_output", h.order_output},
                     {"amplitude_arcsec", h.amplitude_rad * kArcsecPerRad},
                     {"phase_rad", h.phase_rad}});
  }
  return {{"offset_arcsec", fit.offset_rad * kArcsecPerRad},
          {"terms", terms},
          {"rms_residual_arcsec", fit.rms_residual_rad * kArcsecPerRad}};
}

nlohmann::json to_json(const TwinResidual& r) {
  return {
      {"mean_arcsec", r.mean_arcsec}, {"rms_arcsec", r.rms_arcsec}, {"p2p_arcsec", r.p2p_arcsec}};
}

}  // namespace wavebench::procedures
