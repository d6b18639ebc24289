#include "wavebench/analysis/window.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace wavebench::analysis {
namespace {

// Cosine-sum coefficients a_k of w[n] = sum_k (-1)^k a_k cos(2 pi k n / N). The flat-top is
// the five-term window of Matlab's flattopwin / SRS (scalloping loss below 0.01 dB).
std::array<double, 5> cosine_terms(Window window) {
  switch (window) {
    case Window::kHann:
      return {0.5, 0.5, 0, 0, 0};
    case Window::kFlatTop:
      return {0.21557895, 0.41663158, 0.277263158, 0.083578947, 0.006947368};
    case Window::kRectangular:
      break;
  }
  return {1, 0, 0, 0, 0};
}

}  // namespace

double window_coefficient(Window window, std::size_t i, std::size_t n) {
  const auto a = cosine_terms(window);
  const double phase = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
  double value = 0;
  double sign = 1;
  for (std::size_t k = 0; k < a.size(); ++k) {
    value += sign * a[k] * std::cos(static_cast<double>(k) * phase);
    sign = -sign;
  }
  return value;
}

std::vector<double> window_coefficients(Window window, std::size_t n) {
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i) w[i] = window_coefficient(window, i, n);
  return w;
}

double coherent_gain(Window window) {
  return cosine_terms(window)[0];
}

const char* window_name(Window window) {
  switch (window) {
    case Window::kHann:
      return "hann";
    case Window::kFlatTop:
      return "flattop";
    case Window::kRectangular:
      return "rectangular";
  }
  return "unknown";
}

double window_lobe(Window window, double offset_bins) {
  // Long-record limit of the window's DTFT: sinc kernels shifted by whole bins. The kernel's
  // linear phase flips the sign of every odd shift, which cancels the (-1)^k of the window
  // formula, so each shift k enters with +a_k / 2.
  const auto a = cosine_terms(window);
  double sum = 0;
  for (int m = -4; m <= 4; ++m) {
    const auto k = static_cast<std::size_t>(m < 0 ? -m : m);
    const double c = k == 0 ? a[0] : 0.5 * a[k];
    const double x = offset_bins - m;
    const double kernel =
        std::abs(x) < 1e-9 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
    sum += c * kernel;
  }
  return std::abs(sum) / a[0];
}

}  // namespace wavebench::analysis
