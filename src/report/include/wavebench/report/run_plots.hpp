#pragma once
// The plots of a bench run (bench.md §4, §5), each built only when the run folder holds what it
// needs: static TE against output angle per direction and load; the dynamic TE trace and its
// spectrum with named peaks; the torque–twist (lost-motion, hysteresis) curve with the fitted
// three-segment stiffness over it; the twin against the measurement and the residual.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/report/figure.hpp"
#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

// TE of a dynamic record over its steady-speed part (run-in and stop left out).
struct DynamicTrace {
  std::vector<double> time_s;            // from the first steady sample
  std::vector<double> output_angle_deg;  // θ2 from the first steady sample
  std::vector<double> te_arcsec;
  double input_speed_hz = 0;  // mean f_H over the steady part
};

// nullopt when fewer than 16 samples carry both angles or the input never turns steadily.
std::optional<DynamicTrace> dynamic_trace(const std::vector<storage::SyncSample>& samples,
                                          const metrology::GearSense& sense);
// The analysed trace the dynamic results carry ("trace": time_s, output_angle_deg,
// te_arcsec), nullopt when absent or malformed.
std::optional<DynamicTrace> dynamic_trace(const nlohmann::json& dynamic);

// Torque–twist points: the fit's own points when results.json carries them (a "points" or
// "record" list of {torque_nm, twist_rad|twist_arcmin|twist_arcsec, travel}), else every
// sample with TE as the twist.
struct TorqueTwistCurve {
  std::vector<double> twist_arcmin, torque_nm;
  std::vector<int> travel;  // +1 forward, -1 reverse (the torque's sign when not given)
  std::string twist_label;
  bool from_samples = false;
};
std::optional<TorqueTwistCurve> torque_twist_from_results(const nlohmann::json& fit);
std::optional<TorqueTwistCurve> torque_twist_from_samples(
    const std::vector<storage::SyncSample>& samples, const metrology::GearSense& sense);
// The same from a sample log's records [0, records), read page by page: every point while
// there are at most kTorqueTwistPoints, else the first point of each occupied cell of a grid
// over the curve's extent per direction of travel (a scatter shows no more), so the memory
// is bounded whatever the run's length.
inline constexpr std::size_t kTorqueTwistPoints = 20000;
std::optional<TorqueTwistCurve> torque_twist_from_log(const std::filesystem::path& log,
                                                      std::uint64_t records,
                                                      const metrology::GearSense& sense);

// `passes`: results.json "static" list. One row per load, forward and reverse in each.
std::optional<Figure> static_te_figure(const nlohmann::json& passes);
struct DynamicPlotData;  // dynamic_plot_data.hpp
// TE against output angle and against time, as the envelopes hold them.
std::optional<Figure> dynamic_te_figure(const DynamicPlotData& data);
// The spectrum of `data` (when given and it has one) in Hz and in output orders, the analysis'
// named peaks marked, predicted components above Nyquist marked "aliased" where they fold to.
// Without a spectrum, the named peaks alone as stems.
std::optional<Figure> dynamic_spectrum_figure(const DynamicPlotData* data,
                                              const nlohmann::json& dynamic, double ratio);
// Torque against twist, with the fitted curve of `fit` (results.json lost-motion fit:
// stiffness k1..k3, t1, t2) drawn over it per direction of travel, each branch's offset from
// its points.
std::optional<Figure> hysteresis_figure(const TorqueTwistCurve& curve, const nlohmann::json* fit);
std::optional<Figure> twin_figure(const TwinTrace& twin);

}  // namespace wavebench::report
