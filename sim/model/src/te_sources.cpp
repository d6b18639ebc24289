// Seed 001's error-source form of the transmission error (model.md §3).
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "wavebench/model/simulation.hpp"

namespace wavebench::model {
namespace {

struct SourceKind {
  TeFamily family;
  const char* description;
};

// Which family (and so which orders) a named source belongs to; the table of model.md §3.
SourceKind classify(const std::string& name) {
  if (name == "dF_i1")
    return {TeFamily::kTangentialOutput, "Flexspline tangential composite error"};
  if (name == "dF_i3") {
    return {TeFamily::kTangentialOutput, "output circular spline tangential composite error"};
  }
  if (name == "dF_i2") {
    return {TeFamily::kTangentialFixed, "fixed circular spline tangential composite error"};
  }
  if (name == "dS_fix") return {TeFamily::kHousing, "housing bore misalignment"};
  if (name.rfind("df_i", 0) == 0) return {TeFamily::kToothMesh, "base pitch error"};
  if (name.rfind("T1k_", 0) == 0) return {TeFamily::kOutputAssembly, "output-side assembly error"};
  if (name.rfind("T1l_", 0) == 0) {
    return {TeFamily::kWaveGenerator, "wave-generator/input assembly error"};
  }
  throw std::invalid_argument("unknown error source '" + name +
                              "' (expected dF_i1, dF_i2, dF_i3, dS_fix, df_iN, T1k_N or T1l_N)");
}

}  // namespace

std::vector<TeTerm> te_terms_from_error_sources(const ErrorSourceSet& set,
                                                const GearGeometry& geometry) {
  if (!(set.pitch_diameter_m > 0)) throw std::invalid_argument("pitch diameter must be > 0");
  if (!(set.tooth_pairs_in_contact > 0)) {
    throw std::invalid_argument("tooth pairs in contact must be > 0");
  }
  const double cos_a = std::cos(set.pressure_angle_rad);
  const double u = geometry.wave_number;
  // 412.5296/d_w [arcsec per um at d_w in mm] is 2/d_w in SI; with the 1/(2 N_c) in front the
  // common factor is 1/(d_w N_c) rad per metre of tolerance.
  const double common = 1.0 / (set.pitch_diameter_m * set.tooth_pairs_in_contact);
  std::vector<TeTerm> terms;
  terms.reserve(set.sources.size());
  for (const auto& src : set.sources) {
    const SourceKind kind = classify(src.name);
    TeTerm term;
    term.source = src.name + " (" + kind.description + ")";
    term.family = kind.family;
    term.phase_rad = src.phase_rad;
    double factor = 1.0;
    switch (kind.family) {
      case TeFamily::kTangentialOutput:
        term.order_input = u;
        term.order_output = u;
        break;
      case TeFamily::kOutputAssembly:
        term.order_input = u;
        term.order_output = u;
        factor = 1.0 / cos_a;
        break;
      case TeFamily::kTangentialFixed:
      case TeFamily::kHousing:
        term.order_input = u;
        break;
      case TeFamily::kToothMesh:
        term.order_input = u * geometry.z_circ;
        break;
      case TeFamily::kWaveGenerator:
        term.order_input = 1;
        factor = 1.0 / (geometry.ratio * cos_a * cos_a);
        break;
      default:
        break;
    }
    term.amplitude_rad = factor * src.tolerance_m * common;
    terms.push_back(term);
  }
  return terms;
}

double te_term_frequency_hz(const TeTerm& term, const GearGeometry& geometry, double omega1) {
  const double f_h = omega1 / (2.0 * std::numbers::pi);
  return (term.order_input + term.order_output / geometry.ratio) * f_h;
}

}  // namespace wavebench::model
