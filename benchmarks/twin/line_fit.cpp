#include "line_fit.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

namespace wavebench::bench {

std::vector<double> fit_line_amplitudes(std::span<const double> t, std::span<const double> x,
                                        std::span<const double> freqs_hz) {
  const auto n = static_cast<Eigen::Index>(t.size());
  const auto m = static_cast<Eigen::Index>(freqs_hz.size());
  Eigen::MatrixXd a(n, 2 * m + 2);
  Eigen::VectorXd b(n);
  const double t0 = t.front();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double ti = t[static_cast<std::size_t>(i)];
    for (Eigen::Index k = 0; k < m; ++k) {
      const double w = 2 * std::numbers::pi * freqs_hz[static_cast<std::size_t>(k)];
      a(i, 2 * k) = std::sin(w * ti);
      a(i, 2 * k + 1) = std::cos(w * ti);
    }
    a(i, 2 * m) = 1.0;
    a(i, 2 * m + 1) = ti - t0;
    b(i) = x[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  std::vector<double> amp(freqs_hz.size());
  for (Eigen::Index k = 0; k < m; ++k)
    amp[static_cast<std::size_t>(k)] = std::hypot(c(2 * k), c(2 * k + 1));
  return amp;
}

}  // namespace wavebench::bench
