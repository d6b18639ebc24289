#include "wavebench/metrology/lost_motion_uncertainty.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "wavebench/metrology/gear_sense.hpp"

namespace wavebench::metrology {

namespace {

struct Source {
  const char* name;
  char type;
  bool varies;
  double variance;  // mean over the points [rad²]
};

struct Spread {
  double sum = 0, sum_squares = 0;
  int n = 0;
  void add(double x) {
    sum += x;
    sum_squares += x * x;
    ++n;
  }
  double variance() const {
    if (n < 2) return 0;
    const double m = sum / n;
    return std::max(0.0, (sum_squares - n * m * m) / (n - 1));
  }
};

UncertainFigure shared_out(double value, const Spread& spread, const std::vector<Source>& sources,
                           double total_variance) {
  UncertainFigure f;
  f.value = value;
  const double var = spread.variance();
  for (const auto& s : sources) {
    const double share = total_variance > 0 ? s.variance / total_variance : 0;
    f.add(s.name, std::sqrt(var * share), s.type, s.varies);
  }
  return f;
}

}  // namespace

LostMotionUncertainty lost_motion_uncertainty(std::span<const TorqueTwistPoint> record,
                                              const LostMotionOptions& options,
                                              const LostMotionResult& result,
                                              const LostMotionUncertaintyInputs& inputs) {
  const std::size_t n = record.size();
  double noise_variance = 0;
  for (std::size_t i = 0; i < n && i < inputs.twist_noise_rad.size(); ++i) {
    noise_variance += inputs.twist_noise_rad[i] * inputs.twist_noise_rad[i];
  }
  noise_variance /= static_cast<double>(std::max<std::size_t>(n, 1));
  const double q_out = quantisation_standard(inputs.output_resolution_rad);
  const double q_in = quantisation_standard(inputs.input_resolution_rad / inputs.ratio);
  const double misfit = result.stiffness.rms_residual_rad;
  const std::vector<Source> sources{
      {"output encoder quantisation", 'B', false, q_out * q_out},
      {"input encoder quantisation (/N)", 'B', false, q_in * q_in},
      {"noise after window averaging", 'A', true, noise_variance},
      {"fit misfit (RMS residual of the three-segment law)", 'A', true, misfit * misfit}};
  double total = 0;
  for (const auto& s : sources) total += s.variance;
  const double u_point = std::sqrt(total);

  Spread lm, backlash, k1, k2, k3, t1, t2;
  std::mt19937_64 rng(inputs.seed);
  std::normal_distribution<double> unit(0.0, u_point);
  std::vector<TorqueTwistPoint> perturbed(record.begin(), record.end());
  for (int d = 0; d < inputs.draws && u_point > 0; ++d) {
    for (std::size_t i = 0; i < n; ++i) perturbed[i].twist_rad = record[i].twist_rad + unit(rng);
    try {
      const auto r = analyse_lost_motion(perturbed, options);
      lm.add(r.lost_motion_rad * kArcminPerRad);
      backlash.add(r.backlash_rad * kArcminPerRad);
      k1.add(r.stiffness.k1);
      k2.add(r.stiffness.k2);
      k3.add(r.stiffness.k3);
      t1.add(r.stiffness.t1);
      t2.add(r.stiffness.t2);
    } catch (const std::invalid_argument&) {
      // A draw the fit cannot take is left out; the others still measure the spread.
    }
  }
  LostMotionUncertainty u;
  u.lost_motion_arcmin = shared_out(result.lost_motion_rad * kArcminPerRad, lm, sources, total);
  u.backlash_arcmin = shared_out(result.backlash_rad * kArcminPerRad, backlash, sources, total);
  u.k1_nm_per_rad = shared_out(result.stiffness.k1, k1, sources, total);
  u.k2_nm_per_rad = shared_out(result.stiffness.k2, k2, sources, total);
  u.k3_nm_per_rad = shared_out(result.stiffness.k3, k3, sources, total);
  u.t1_nm = shared_out(result.stiffness.t1, t1, sources, total);
  u.t2_nm = shared_out(result.stiffness.t2, t2, sources, total);
  return u;
}

nlohmann::json fit_uncertainty_json(const LostMotionUncertainty& u) {
  return {{"lost_motion_arcmin", to_json(u.lost_motion_arcmin)},
          {"backlash_arcmin", to_json(u.backlash_arcmin)}};
}

nlohmann::json stiffness_uncertainty_json(const LostMotionUncertainty& u) {
  return {{"k1_nm_per_rad", to_json(u.k1_nm_per_rad)},
          {"k2_nm_per_rad", to_json(u.k2_nm_per_rad)},
          {"k3_nm_per_rad", to_json(u.k3_nm_per_rad)},
          {"t1_nm", to_json(u.t1_nm)},
          {"t2_nm", to_json(u.t2_nm)}};
}

}  // namespace wavebench::metrology
