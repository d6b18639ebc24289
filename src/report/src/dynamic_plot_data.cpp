#include "wavebench/report/dynamic_plot_data.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "wavebench/analysis/min_max_envelope.hpp"
#include "wavebench/model/angle_units.hpp"
#include "wavebench/report/averaged_spectrum.hpp"
#include "wavebench/report/sample_log_scan.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
constexpr double kNoTime = -std::numeric_limits<double>::infinity();
constexpr std::uint64_t kMaxBlocks = 4096;

// As dynamic_trace(): the input speed over windows of w samples, long enough that a late SYNC's
// timestamp does not dominate; every k-th window into the median past kSpeedMedianWindows.
std::size_t window_for(std::uint64_t n) {
  return std::clamp<std::size_t>(static_cast<std::size_t>(n / 50), 1, 200);
}
std::uint64_t median_stride(std::uint64_t n) {
  const std::uint64_t windows = n > window_for(n) ? n - window_for(n) : 0;
  return std::max<std::uint64_t>(1, (windows + kSpeedMedianWindows - 1) / kSpeedMedianWindows);
}

struct AngleSample {
  double t = 0, th_in = 0, th_out = 0;
  std::uint64_t record = 0;
  double angle_lo = 0, angle_hi = 0;  // of the steady part up to this sample (slow path)
};

// The records dynamic_trace() takes: both angles valid, a time after the previous one's.
// visit(j, sample) with j counting those records from `first_j`; `previous_t` is the time of
// the one taken before `from`. A visitor returning false stops the scan.
template <class Visit>
void scan_angles(const fs::path& log, std::uint64_t from, std::uint64_t end, Visit&& visit,
                 double previous_t = kNoTime, std::uint64_t first_j = 0,
                 std::size_t page_records = kScanPageRecords) {
  std::uint64_t j = first_j;
  double last_t = previous_t;
  std::uint64_t record = from;
  scan_sample_log(
      log, from, end,
      [&](const storage::SyncSample& s) {
        const std::uint64_t r = record++;
        if (!s.valid(storage::kThetaInValid) || !s.valid(storage::kThetaOutValid)) return true;
        const double t = 1e-9 * static_cast<double>(s.receive_time_ns);
        if (t <= last_t) return true;
        last_t = t;
        const AngleSample a{t, s.theta_in_rad, s.theta_out_rad, r, 0, 0};
        if constexpr (std::is_same_v<decltype(visit(j, a)), bool>) {
          return visit(j++, a);
        } else {
          visit(j++, a);
          return true;
        }
      },
      page_records);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// The steady part: its first sample, its last, how many.
struct SteadyPart {
  AngleSample first, last;
  std::uint64_t count = 0;
  double angle_lo = 0, angle_hi = 0;  // a first guess when from the summary
};

struct SteadyBand {
  double steady = 0;
  bool contains(double v) const { return std::abs(v - steady) <= 0.02 * std::abs(steady); }
  bool meets(double lo, double hi) const {
    return lo <= steady + 0.02 * std::abs(steady) && hi >= steady - 0.02 * std::abs(steady);
  }
};

// Without a summary: the median in one pass, the bounds in another (each sample carries the
// angle range of the part up to it, so the part's range is known at its end).
std::optional<SteadyPart> steady_part_in_passes(const fs::path& log, const SampleLogFacts& facts,
                                                const metrology::GearSense& sense) {
  const std::uint64_t n = facts.angle_samples;
  const std::size_t w = window_for(n);
  const std::uint64_t stride = median_stride(n);
  std::vector<AngleSample> ring(w + 1);
  const auto speed_to = [&](std::uint64_t i, const AngleSample& s) {
    const AngleSample& a = ring[i % (w + 1)];
    return (s.th_in - a.th_in) / (s.t - a.t);
  };
  std::vector<double> speeds;
  scan_angles(log, 0, facts.records, [&](std::uint64_t j, const AngleSample& s) {
    if (j >= w && (j - w) % stride == 0) speeds.push_back(speed_to(j - w, s));
    ring[j % (w + 1)] = s;
  });
  const SteadyBand band{median(std::move(speeds))};
  if (!(std::abs(band.steady) > 1e-6)) return std::nullopt;

  std::optional<std::uint64_t> start;
  SteadyPart part;
  std::uint64_t last_index = 0;
  bool have_last = false;
  double lo = 0, hi = 0;
  scan_angles(log, 0, facts.records, [&](std::uint64_t j, AngleSample s) {
    bool steady_window = false;
    if (j >= w) {
      steady_window = band.contains(speed_to(j - w, s));
      if (steady_window && !start) {
        start = j;
        part.first = s;
      }
    }
    if (start) {
      const double a =
          (sense.model_output_angle(s.th_out) - sense.model_output_angle(part.first.th_out)) *
          model::kDegPerRad;
      lo = j == *start ? a : std::min(lo, a);
      hi = j == *start ? a : std::max(hi, a);
      s.angle_lo = lo;
      s.angle_hi = hi;
    }
    if (steady_window && j - w >= *start) {
      part.last = ring[(j - w) % (w + 1)];
      last_index = j - w;
      have_last = true;
    }
    ring[j % (w + 1)] = s;
  });
  if (!start || !have_last || last_index + 1 < *start + 16) return std::nullopt;
  part.count = last_index + 1 - *start;
  part.angle_lo = part.last.angle_lo;
  part.angle_hi = part.last.angle_hi;
  return part;
}

// With the summary: the first steady window from the first blocks whose speeds meet the band,
// the last from the last such blocks, each block read with the w samples after it.
std::optional<SteadyPart> steady_part_from_summary(const fs::path& log, const SampleLogFacts& facts,
                                                   const InputSpeedSummary& summary,
                                                   const metrology::GearSense& sense) {
  const std::uint64_t n = facts.angle_samples;
  const std::size_t w = summary.window();
  const SteadyBand band{median(summary.median_speeds())};
  if (!(std::abs(band.steady) > 1e-6)) return std::nullopt;
  const auto& blocks = summary.blocks();
  const std::uint64_t b_len = summary.block_samples();
  // The windows starting in block b: their first and last steady one, with the samples at
  // both ends of each.
  struct Found {
    std::uint64_t i = 0;
    AngleSample at_i, at_i_plus_w;
  };
  const auto scan_block = [&](std::size_t b, bool want_last) -> std::optional<Found> {
    const std::uint64_t j0 = b * b_len;
    const std::uint64_t i_end = std::min(j0 + b_len, n - w);  // windows [j0, i_end)
    std::vector<AngleSample> ring(w + 1);
    std::optional<Found> found;
    // Pages of about the block's size: a block is a small part of the log.
    const auto page = static_cast<std::size_t>(std::min<std::uint64_t>(b_len + w + 64, 1 << 15));
    scan_angles(
        log, blocks[b].record, facts.records,
        [&](std::uint64_t j, const AngleSample& s) {
          if (j >= j0 + w) {
            const std::uint64_t i = j - w;
            const AngleSample& a = ring[i % (w + 1)];
            if (band.contains((s.th_in - a.th_in) / (s.t - a.t))) {
              found = Found{i, a, s};
              if (!want_last) return false;
            }
          }
          ring[j % (w + 1)] = s;
          return j + 1 < i_end + w;
        },
        blocks[b].previous_t, j0, page);
    return found;
  };
  std::optional<Found> first, last;
  for (std::size_t b = 0; b < blocks.size() && !first; ++b) {
    if (blocks[b].any && band.meets(blocks[b].lo, blocks[b].hi)) first = scan_block(b, false);
  }
  for (std::size_t b = blocks.size(); b-- > 0 && first && !last;) {
    if (blocks[b].any && band.meets(blocks[b].lo, blocks[b].hi)) last = scan_block(b, true);
  }
  if (!first || !last) return std::nullopt;
  const std::uint64_t start = first->i + w;
  if (last->i + 1 < start + 16) return std::nullopt;
  SteadyPart part;
  part.first = first->at_i_plus_w;
  part.last = last->at_i;
  part.count = last->i + 1 - start;
  const double a_last =
      (sense.model_output_angle(part.last.th_out) - sense.model_output_angle(part.first.th_out)) *
      model::kDegPerRad;
  part.angle_lo = std::min(0.0, a_last);
  part.angle_hi = std::max(0.0, a_last);
  return part;
}

DynamicPlotData finish(analysis::MinMaxEnvelope& by_angle, analysis::MinMaxEnvelope& by_time,
                       const AveragedSpectrum& spectrum, std::size_t segment) {
  DynamicPlotData d;
  d.te_by_angle = by_angle.result();
  d.te_by_time = by_time.result();
  d.spectrum = spectrum.result();
  d.spectrum_segments = segment == 0 ? 0 : spectrum.segments();
  return d;
}

}  // namespace

InputSpeedSummary::InputSpeedSummary(std::uint64_t expected_samples)
    : expected_(expected_samples),
      w_(window_for(expected_samples)),
      stride_(median_stride(expected_samples)),
      block_(std::max<std::uint64_t>(1, (expected_samples + kMaxBlocks - 1) / kMaxBlocks)),
      ring_(w_ + 1),
      previous_t_(kNoTime) {}

void InputSpeedSummary::add(std::uint64_t record, double t, double theta_in_rad) {
  const std::uint64_t j = n_++;
  if (j % block_ == 0) blocks_.push_back({record, previous_t_, 0, 0, false});
  previous_t_ = t;
  if (j >= w_) {
    const std::uint64_t i = j - w_;
    const auto& [t_i, in_i] = ring_[i % (w_ + 1)];
    const double speed = (theta_in_rad - in_i) / (t - t_i);
    if (i % stride_ == 0) speeds_.push_back(speed);
    Block& b = blocks_[i / block_];
    b.lo = b.any ? std::min(b.lo, speed) : speed;
    b.hi = b.any ? std::max(b.hi, speed) : speed;
    b.any = true;
  }
  ring_[j % (w_ + 1)] = {t, theta_in_rad};
}

bool InputSpeedSummary::fits(std::uint64_t angle_samples) const {
  return angle_samples == n_ && window_for(angle_samples) == w_ &&
         median_stride(angle_samples) == stride_;
}

DynamicPlotData reduce_dynamic_trace(const DynamicTrace& trace, double ratio, std::size_t columns,
                                     analysis::SpectrumAnalyser& analyser) {
  const std::size_t n = trace.te_arcsec.size();
  const auto [lo, hi] =
      std::minmax_element(trace.output_angle_deg.begin(), trace.output_angle_deg.end());
  analysis::MinMaxEnvelope by_angle(n ? *lo : 0, n ? *hi : 0, columns, 1);
  analysis::MinMaxEnvelope by_time(n ? trace.time_s.front() : 0, n ? trace.time_s.back() : 0,
                                   columns, 1);
  const double span = n > 1 ? trace.time_s.back() - trace.time_s.front() : 0;
  const double rate = span > 0 ? static_cast<double>(n - 1) / span : 0;
  const std::size_t segment =
      spectrum_segment_samples(n, rate, ratio > 0 ? trace.input_speed_hz / ratio : 0);
  AveragedSpectrum spectrum(segment, analyser);
  for (std::size_t i = 0; i < n; ++i) {
    by_angle.add(trace.output_angle_deg[i], trace.te_arcsec[i]);
    by_time.add(trace.time_s[i], trace.te_arcsec[i]);
    spectrum.add(trace.time_s[i], trace.te_arcsec[i]);
  }
  DynamicPlotData d = finish(by_angle, by_time, spectrum, segment);
  d.input_speed_hz = trace.input_speed_hz;
  d.samples = n;
  return d;
}

std::optional<DynamicPlotData> dynamic_plot_data(const fs::path& log, const SampleLogFacts& facts,
                                                 const metrology::GearSense& sense,
                                                 std::size_t columns,
                                                 analysis::SpectrumAnalyser& analyser) {
  if (facts.angle_samples < 16 || !(sense.ratio > 0)) return std::nullopt;
  const auto part = facts.input_speeds && facts.input_speeds->fits(facts.angle_samples)
                        ? steady_part_from_summary(log, facts, *facts.input_speeds, sense)
                        : steady_part_in_passes(log, facts, sense);
  if (!part) return std::nullopt;

  // The part into the envelopes and the spectrum. The angle's range is a guess from the part's
  // ends when it came from the summary: should the angle leave it, a second pass draws it.
  const double span = part->last.t - part->first.t;
  const double input_hz =
      span > 0 ? std::abs(part->last.th_in - part->first.th_in) / span / (2 * std::numbers::pi) : 0;
  const double rate = span > 0 ? static_cast<double>(part->count - 1) / span : 0;
  const std::size_t segment =
      spectrum_segment_samples(static_cast<std::size_t>(part->count), rate, input_hz / sense.ratio);
  const double out0 = sense.model_output_angle(part->first.th_out);
  const auto angle_of = [&](const AngleSample& s) {
    return (sense.model_output_angle(s.th_out) - out0) * model::kDegPerRad;
  };
  const auto te_of = [&](const AngleSample& s) {
    return sense.transmission_error(s.th_in, s.th_out) * metrology::kArcsecPerRad;
  };
  analysis::MinMaxEnvelope by_angle(part->angle_lo, part->angle_hi, columns, 1);
  analysis::MinMaxEnvelope by_time(0, span, columns, 1);
  AveragedSpectrum spectrum(segment, analyser);
  double lo = 0, hi = 0;
  scan_angles(log, part->first.record, part->last.record + 1,
              [&](std::uint64_t, const AngleSample& s) {
                const double time = s.t - part->first.t;
                const double angle = angle_of(s);
                const double te = te_of(s);
                lo = std::min(lo, angle);
                hi = std::max(hi, angle);
                by_angle.add(angle, te);
                by_time.add(time, te);
                spectrum.add(time, te);
              });
  DynamicPlotData d = finish(by_angle, by_time, spectrum, segment);
  if (by_angle.samples_outside_range() > 0) {
    analysis::MinMaxEnvelope redrawn(lo, hi, columns, 1);
    scan_angles(log, part->first.record, part->last.record + 1,
                [&](std::uint64_t, const AngleSample& s) { redrawn.add(angle_of(s), te_of(s)); });
    d.te_by_angle = redrawn.result();
  }
  d.input_speed_hz = input_hz;
  d.samples = static_cast<std::size_t>(part->count);
  return d;
}

}  // namespace wavebench::report
