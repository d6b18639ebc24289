#include "wavebench/analysis/peak_attribution.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "wavebench/model/simulation.hpp"

namespace wavebench::analysis {
namespace {

struct TermLine {
  const model::TeTerm* term;
  std::string name;     // source label without the description in brackets
  double frequency_hz;  // true
  double apparent_hz;   // after folding
  bool aliased;
  std::complex<double> contribution;  // H(f) A e^{i phi} in the analysed signal
};

std::string short_name(const std::string& source) {
  const auto bracket = source.find(" (");
  return bracket == std::string::npos ? source : source.substr(0, bracket);
}

bool same_frequency(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
}

}  // namespace

double folded_frequency_hz(double frequency_hz, double sample_rate_hz) {
  double f = std::fmod(std::abs(frequency_hz), sample_rate_hz);
  if (f > 0.5 * sample_rate_hz) f = sample_rate_hz - f;
  return f;
}

double bin_tolerance_hz(Window window, double resolution_hz) {
  double bins = 2.0;
  if (window == Window::kFlatTop) bins = 5.0;
  if (window == Window::kRectangular) bins = 1.5;
  return bins * resolution_hz;
}

std::vector<AttributedPeak> attribute_peaks(const std::vector<SpectralPeak>& peaks,
                                            const AttributionInput& input) {
  std::vector<TermLine> lines;
  for (const auto& term : input.terms) {
    if (term.amplitude_rad == 0) continue;
    TermLine line{&term, short_name(term.source), 0, 0, false, {}};
    line.frequency_hz =
        std::abs(model::te_term_frequency_hz(term, input.geometry, input.mean_input_speed));
    line.apparent_hz = folded_frequency_hz(line.frequency_hz, input.sample_rate_hz);
    line.aliased = line.frequency_hz > 0.5 * input.sample_rate_hz;
    // A folded line from the mirrored side of a Nyquist zone has its phase conjugated.
    const double zone = std::fmod(line.frequency_hz, input.sample_rate_hz);
    const bool mirrored = zone > 0.5 * input.sample_rate_hz;
    const std::complex<double> h =
        input.use_transfer ? te_transfer(input.linear, input.signal, line.frequency_hz) : 1.0;
    std::complex<double> c = h * std::polar(std::abs(term.amplitude_rad), term.phase_rad);
    line.contribution = mirrored ? std::conj(c) : c;
    lines.push_back(line);
  }

  const double tolerance = bin_tolerance_hz(input.window, input.resolution_hz);
  std::vector<AttributedPeak> out;
  for (const auto& peak : peaks) {
    AttributedPeak ap;
    ap.frequency_hz = peak.frequency_hz;
    ap.amplitude = peak.amplitude;
    ap.tolerance_hz = tolerance;
    std::vector<const TermLine*> matched;
    for (const auto& line : lines) {
      if (std::abs(line.apparent_hz - peak.frequency_hz) <= tolerance) matched.push_back(&line);
    }
    if (matched.empty()) {
      ap.label = "unattributed";
      // Harmonics and combination tones of the terms: what a nonlinearity (backlash, cubic
      // stiffness) makes of them.
      // Strict comparisons: on a tie the first (larger listed) term keeps the label.
      double best = tolerance * (1 + 1e-12);
      for (std::size_t i = 0; i < lines.size(); ++i) {
        for (int h = 2; h <= 4; ++h) {
          const double f = folded_frequency_hz(h * lines[i].frequency_hz, input.sample_rate_hz);
          if (std::abs(f - peak.frequency_hz) < best) {
            best = std::abs(f - peak.frequency_hz);
            ap.label = "nonlinear: " + std::to_string(h) + "*" + lines[i].name;
          }
        }
        for (std::size_t j = i + 1; j < lines.size(); ++j) {
          if (same_frequency(lines[i].frequency_hz, lines[j].frequency_hz)) continue;
          const double sum = folded_frequency_hz(lines[i].frequency_hz + lines[j].frequency_hz,
                                                 input.sample_rate_hz);
          const double diff = std::abs(lines[i].frequency_hz - lines[j].frequency_hz);
          if (std::abs(sum - peak.frequency_hz) < best) {
            best = std::abs(sum - peak.frequency_hz);
            ap.label = "nonlinear: " + lines[i].name + "+" + lines[j].name;
          }
          if (std::abs(diff - peak.frequency_hz) < best) {
            best = std::abs(diff - peak.frequency_hz);
            ap.label = "nonlinear: " + lines[i].name + "-" + lines[j].name;
          }
        }
      }
      out.push_back(ap);
      continue;
    }
    ap.label = "te";
    // Terms at one frequency add as phasors; distinct (unresolved) frequencies add in power.
    std::vector<std::pair<double, std::complex<double>>> groups;
    double magnitude_sum = 0;
    for (const auto* line : matched) {
      magnitude_sum += std::abs(line->contribution);
      auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
        return same_frequency(g.first, line->frequency_hz);
      });
      if (it == groups.end()) {
        groups.emplace_back(line->frequency_hz, line->contribution);
      } else {
        it->second += line->contribution;
      }
    }
    double power = 0;
    for (const auto& g : groups) power += std::norm(g.second);
    ap.predicted_amplitude = std::sqrt(power);
    for (const auto* line : matched) {
      PeakSource src;
      src.source = line->term->source;
      src.term_frequency_hz = line->frequency_hz;
      src.predicted_amplitude = std::abs(line->contribution);
      src.aliased = line->aliased;
      src.share = magnitude_sum > 0 ? src.predicted_amplitude / magnitude_sum
                                    : 1.0 / static_cast<double>(matched.size());
      const auto group = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
        return same_frequency(g.first, line->frequency_hz);
      });
      // Projection on the group's resultant; a fully cancelled group falls back to magnitudes.
      src.in_phase_share =
          power > 1e-24 * magnitude_sum * magnitude_sum && std::norm(group->second) > 0
              ? std::real(line->contribution * std::conj(group->second)) / power
              : src.share;
      ap.aliased = ap.aliased || line->aliased;
      ap.sources.push_back(src);
    }
    std::sort(ap.sources.begin(), ap.sources.end(),
              [](const PeakSource& p, const PeakSource& q) { return p.share > q.share; });
    out.push_back(ap);
  }
  return out;
}

}  // namespace wavebench::analysis
