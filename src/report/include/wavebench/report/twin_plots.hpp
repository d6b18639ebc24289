#pragma once
// The plots of a twin run, built from plain data so that they do not depend on how the
// analysis stores its results.

#include <string>
#include <vector>

#include "wavebench/model/simulation.hpp"
#include "wavebench/report/figure.hpp"

namespace wavebench::report {

// TE [arcsec] and output acceleration over the whole record, and a zoom on its first
// `zoom_seconds`.
Figure time_response_figure(const model::SampledResponse& response, const std::string& title,
                            double zoom_seconds);

struct NamedPeak {
  double frequency_hz = 0;
  double amplitude = 0;
  std::string label;  // e.g. "dF_i1, dF_i3"
};

// Amplitude spectrum, log amplitude, peaks labelled at the peaks; below it a linear zoom on
// the largest peak so lines a fraction of a hertz apart can be told apart.
Figure spectrum_figure(const std::vector<double>& frequency_hz,
                       const std::vector<double>& amplitude, const std::vector<NamedPeak>& peaks,
                       const std::string& amplitude_label, const std::string& title);

struct PortraitPanel {
  std::string title, x_label, v_label;
  std::vector<double> x, v;
};

// Phase portraits side by side (e.g. twist against its rate, output angle against speed).
Figure phase_portrait_figure(const std::vector<PortraitPanel>& panels, const std::string& title);

Figure poincare_figure(const std::vector<double>& x, const std::vector<double>& v,
                       const std::string& x_label, const std::string& v_label,
                       const std::string& motion_class, const std::string& title);

// One direction of a speed sweep: per speed, the Poincaré values and the response amplitude.
struct SweepBranch {
  std::string label;  // "up", "down"
  std::vector<double> speed_rpm;
  std::vector<std::vector<double>> section_values;
  std::vector<double> amplitude;
};

Figure bifurcation_figure(const std::vector<SweepBranch>& branches, const std::string& value_label,
                          const std::string& amplitude_label,
                          const std::vector<double>& jump_speeds_rpm, const std::string& title);

}  // namespace wavebench::report
