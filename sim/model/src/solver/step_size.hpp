#pragma once
// Pieces the adaptive integrators share: the weighted error norm and the first-step guess.

#include <cmath>
#include <cstddef>

namespace wavebench::model::solver::detail {

// RMS of err[i] / (atol*scale[i] + rtol*max(|a[i]|, |b[i]|)).
inline double weighted_rms(const double* err, const double* a, const double* b, const double* scale,
                           std::size_t n, double atol, double rtol) {
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double sk = atol * scale[i] + rtol * std::fmax(std::fabs(a[i]), std::fabs(b[i]));
    const double r = err[i] / sk;
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(n));
}

// Hairer's HINIT (Solving ODEs I, §II.4): an explicit Euler probe estimates the second
// derivative; the step makes the local error of an order-p method about the tolerance.
// f0 = f(t0, y0); rhs(t, y, dydt) evaluates f; y1 and f1 are n doubles of scratch.
template <typename Rhs>
double initial_step(Rhs&& rhs, double t0, const double* y0, const double* f0, const double* scale,
                    std::size_t n, double atol, double rtol, int order, double h_max, double* y1,
                    double* f1) {
  double dnf = 0, dny = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double sk = atol * scale[i] + rtol * std::fabs(y0[i]);
    dnf += (f0[i] / sk) * (f0[i] / sk);
    dny += (y0[i] / sk) * (y0[i] / sk);
  }
  double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  if (h_max > 0) h = std::fmin(h, h_max);
  for (std::size_t i = 0; i < n; ++i) y1[i] = y0[i] + h * f0[i];
  rhs(t0 + h, y1, f1);
  double der2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double sk = atol * scale[i] + rtol * std::fabs(y0[i]);
    der2 += ((f1[i] - f0[i]) / sk) * ((f1[i] - f0[i]) / sk);
  }
  der2 = std::sqrt(der2) / h;
  const double der12 = std::fmax(std::fabs(der2), std::sqrt(dnf));
  const double h1 = der12 <= 1e-15 ? std::fmax(1e-6, h * 1e-3)
                                   : std::pow(0.01 / der12, 1.0 / static_cast<double>(order));
  h = std::fmin(100 * h, h1);
  if (h_max > 0) h = std::fmin(h, h_max);
  return h;
}

}  // namespace wavebench::model::solver::detail
