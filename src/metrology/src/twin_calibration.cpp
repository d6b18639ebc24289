#include "wavebench/metrology/twin_calibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "wavebench/metrology/dynamic_te_analysis.hpp"

namespace wavebench::metrology {

void TwinResidualSum::add(double measured_te_rad, double predicted_te_rad) {
  const double v = (measured_te_rad - predicted_te_rad) * kArcsecPerRad;
  sum_ += v;
  squares_ += v * v;
  lo_ = n_ == 0 ? v : std::min(lo_, v);
  hi_ = n_ == 0 ? v : std::max(hi_, v);
  ++n_;
}

TwinResidual TwinResidualSum::result() const {
  if (n_ < 8) {
    throw std::invalid_argument("twin residual: " + std::to_string(n_) +
                                " samples with a measured and a predicted TE; expected at least 8");
  }
  TwinResidual r;
  r.samples = n_;
  r.mean_arcsec = sum_ / static_cast<double>(n_);
  r.rms_arcsec = std::sqrt(squares_ / static_cast<double>(n_));
  r.p2p_arcsec = hi_ - lo_;
  return r;
}

TwinResidual twin_residual(std::span<const double> measured_te_rad,
                           std::span<const double> predicted_te_rad) {
  if (measured_te_rad.size() != predicted_te_rad.size()) {
    throw std::invalid_argument("twin residual: measured has " +
                                std::to_string(measured_te_rad.size()) + " samples, predicted " +
                                std::to_string(predicted_te_rad.size()) +
                                "; expected equal lengths of at least 8");
  }
  TwinResidualSum sum;
  for (std::size_t i = 0; i < measured_te_rad.size(); ++i) {
    sum.add(measured_te_rad[i], predicted_te_rad[i]);
  }
  return sum.result();
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
  // Least squares a block of rows at a time (a run of hours has millions of rows, and the
  // whole matrix would be 8·unknowns bytes per row twice over): the triangular factor of
  // [A | b] is carried from block to block (R of [R_prev; block] is R of all rows so far). At
  // the end min‖Ax − b‖² = min‖R x − c‖² + ρ², solved with column pivoting as before so that
  // a basis the rows cannot tell apart still gives the basic solution.
  const auto p = static_cast<Eigen::Index>(unknowns);
  constexpr Eigen::Index kBlock = 4096;
  Eigen::MatrixXd carried(0, p + 1);
  Eigen::MatrixXd stacked;
  for (std::size_t from = 0; from < n; from += static_cast<std::size_t>(kBlock)) {
    const auto rows = static_cast<Eigen::Index>(std::min<std::size_t>(kBlock, n - from));
    stacked.resize(carried.rows() + rows, p + 1);
    stacked.topRows(carried.rows()) = carried;
    for (Eigen::Index i = 0; i < rows; ++i) {
      const std::size_t k = from + static_cast<std::size_t>(i);
      auto row = stacked.row(carried.rows() + i);
      row(0) = 1.0;
      for (std::size_t j = 0; j < orders.size(); ++j) {
        const double x =
            orders[j].order_input * theta1_rad[k] + orders[j].order_output * theta2_rad[k];
        row(static_cast<Eigen::Index>(1 + 2 * j)) = std::sin(x);
        row(static_cast<Eigen::Index>(2 + 2 * j)) = std::cos(x);
      }
      for (std::size_t r = 0; r < regressors.size(); ++r) {
        row(static_cast<Eigen::Index>(harmonic_unknowns + r)) = regressors[r][k];
      }
      row(p) = te_rad[k];
    }
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(stacked);
    const Eigen::Index kept = std::min<Eigen::Index>(stacked.rows(), p + 1);
    carried = qr.matrixQR().topRows(kept).triangularView<Eigen::Upper>();
  }
  const Eigen::MatrixXd r_top = carried.topLeftCorner(std::min(carried.rows(), p), p);
  const Eigen::VectorXd qtb = carried.col(p).head(r_top.rows());
  const Eigen::VectorXd x = r_top.colPivHouseholderQr().solve(qtb);
  const double rho = carried.rows() > p ? carried(p, p) : 0.0;
  const double squares = (r_top * x - qtb).squaredNorm() + rho * rho;
  HarmonicFit fit;
  fit.offset_rad = x(0);
  for (std::size_t j = 0; j < orders.size(); ++j) {
    // A·sin(u + φ) = A·cos φ·sin u + A·sin φ·cos u
    const double s = x(static_cast<Eigen::Index>(1 + 2 * j));
    const double c = x(static_cast<Eigen::Index>(2 + 2 * j));
    fit.harmonics.push_back({orders[j].name, orders[j].order_input, orders[j].order_output,
                             std::hypot(s, c), std::atan2(c, s)});
  }
  fit.rms_residual_rad = std::sqrt(squares / static_cast<double>(n));
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

}  // namespace wavebench::metrology
