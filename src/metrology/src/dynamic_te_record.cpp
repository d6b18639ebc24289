#include "wavebench/metrology/dynamic_te_record.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace wavebench::metrology {

namespace {
constexpr double kTwoPi = 2 * std::numbers::pi;
}  // namespace

std::size_t smooth_size_at_least(std::size_t n) {
  for (std::size_t m = std::max<std::size_t>(n, 1);; ++m) {
    std::size_t r = m;
    for (const std::size_t p : {2, 3, 5}) {
      while (r % p == 0) r /= p;
    }
    if (r == 1) return m;
  }
}

DynamicTeRecord::DynamicTeRecord(const GearSense& sense, const DynamicTeRecordShape& shape,
                                 std::size_t max_grid_points)
    : sense_(sense),
      shape_(shape),
      filter_(shape.output_direction),
      welch_(std::max<std::size_t>(shape.points_per_revolution, 8), shape.welch,
             shape.welch_analyser) {
  sense_.validate();
  if (shape.output_direction != 1 && shape.output_direction != -1) {
    throw std::invalid_argument("dynamic TE record: output_direction " +
                                std::to_string(shape.output_direction) + "; expected +1 or -1");
  }
  if (shape.points_per_revolution < 8 || shape.max_revolutions < 1 || shape.trace_stride < 1 ||
      shape.trace_capacity < 4) {
    throw std::invalid_argument(
        "dynamic TE record: " + std::to_string(shape.points_per_revolution) +
        " grid points per revolution, " + std::to_string(shape.max_revolutions) +
        " revolutions, trace stride " + std::to_string(shape.trace_stride) + ", trace capacity " +
        std::to_string(shape.trace_capacity) + "; expected at least 8, 1, 1 and 4");
  }
  if (shape.points_per_revolution > max_grid_points / shape.max_revolutions) {
    throw std::invalid_argument(
        "dynamic TE record: a grid of " + std::to_string(shape.points_per_revolution) +
        " points x " + std::to_string(shape.max_revolutions) + " revolutions; expected at most " +
        std::to_string(max_grid_points) + " points");
  }
  sign_ = sense_.direction_sign * shape.output_direction;
  grid_capacity_ = shape.points_per_revolution * shape.max_revolutions;
  grid_step_ = kTwoPi / static_cast<double>(shape.points_per_revolution);
  trace_stride_ = shape.trace_stride;
  grid_.reserve(grid_capacity_ + 2);  // + 2: the in-place transform's extra bin
  trace_t_.reserve(shape.trace_capacity);
  trace_angle_.reserve(shape.trace_capacity);
  trace_te_.reserve(shape.trace_capacity);
}

void DynamicTeRecord::add(const storage::SyncSample& sample) noexcept {
  ++offered_;
  if (!filter_.keep(sample)) return;
  try {
    add_kept(filter_.time_s(sample), sample.theta_in_rad, sample.theta_out_rad);
  } catch (...) {
    // Unreachable: the filter passes only samples later in time and past in angle.
  }
}

void DynamicTeRecord::add_kept(double time_s, double theta_in_rad, double theta_out_rad) {
  const double model_out = sense_.model_output_angle(theta_out_rad);
  if (kept_ == 0) {
    first_t_ = time_s;
    theta2_0_ = model_out;
    theta_in_0_ = theta_in_rad;
  }
  const double t = time_s - first_t_;
  const double angle = sign_ * (model_out - theta2_0_);
  if (kept_ > 0 && !(t > last_t_)) {
    throw std::invalid_argument("dynamic TE: time is not strictly increasing at sample " +
                                std::to_string(kept_) +
                                "; expected a turning gear and increasing timestamps");
  }
  if (kept_ > 0 && !(angle > last_angle_)) {
    throw std::invalid_argument("dynamic TE: output angle is not strictly increasing at sample " +
                                std::to_string(kept_) +
                                "; expected a turning gear and increasing timestamps");
  }
  const double te = sense_.transmission_error(theta_in_rad, theta_out_rad) * kArcsecPerRad;
  ++kept_;
  const double d = te - mean_;
  mean_ += d / static_cast<double>(kept_);
  m2_ += d * (te - mean_);
  if (kept_ == 1) {
    lo_ = hi_ = te;
  } else {
    lo_ = std::min(lo_, te);
    hi_ = std::max(hi_, te);
  }
  if (kept_ >= 3) {
    const double d2 = te - 2 * te_1_ + te_2_;
    second_ss_ += d2 * d2;
  }
  te_2_ = te_1_;
  te_1_ = te;
  extend_grid(angle, te);

  const TracePoint here{t, model_out - theta2_0_, te};
  if (block_count_ == 0) {
    block_min_ = block_max_ = here;
  } else {
    if (te < block_min_.te) block_min_ = here;
    if (te > block_max_.te) block_max_ = here;
  }
  if (++block_count_ == trace_stride_) close_trace_block();

  last_t_ = t;
  last_angle_ = angle;
  last_te_ = te;
  last_theta_in_ = theta_in_rad;
}

void DynamicTeRecord::extend_grid(double angle, double te) {
  if (kept_ == 1) {
    put_grid_point(te);
    return;
  }
  for (;;) {
    const double g = static_cast<double>(grid_points_) * grid_step_;
    if (g > angle) break;
    const double u = (g - last_angle_) / (angle - last_angle_);
    put_grid_point(last_te_ + u * (te - last_te_));
  }
}

void DynamicTeRecord::put_grid_point(double te) {
  if (grid_.size() < grid_capacity_) grid_.push_back(te);  // reserved: never reallocates
  welch_.put(te);
  ++grid_points_;
}

void DynamicTeRecord::close_trace_block() {
  const std::size_t adding = block_min_.t != block_max_.t ? 2 : 1;
  if (trace_t_.size() + adding > trace_t_.capacity()) halve_trace();
  const bool min_first = block_min_.t <= block_max_.t;
  const TracePoint& a = min_first ? block_min_ : block_max_;
  const TracePoint& b = min_first ? block_max_ : block_min_;
  trace_t_.push_back(a.t);
  trace_angle_.push_back(a.angle);
  trace_te_.push_back(a.te);
  if (b.t != a.t) {
    trace_t_.push_back(b.t);
    trace_angle_.push_back(b.angle);
    trace_te_.push_back(b.te);
  }
  block_count_ = 0;
}

// A record longer than its stride was set for (a slower output, a longer wait): every two
// blocks become one with their min and max, and the stride doubles. In place, so add() still
// allocates nothing.
void DynamicTeRecord::halve_trace() {
  std::size_t out = 0, i = 0;
  const std::size_t n = trace_t_.size();
  // Each block left one or two points in time order; pairs of blocks are not marked, so the
  // points are taken four at a time (two blocks of two), keeping their min and max in order.
  while (i < n) {
    const std::size_t end = std::min(n, i + 4);
    std::size_t lo = i, hi = i;
    for (std::size_t k = i; k < end; ++k) {
      if (trace_te_[k] < trace_te_[lo]) lo = k;
      if (trace_te_[k] > trace_te_[hi]) hi = k;
    }
    for (const std::size_t k : {std::min(lo, hi), std::max(lo, hi)}) {
      trace_t_[out] = trace_t_[k];
      trace_angle_[out] = trace_angle_[k];
      trace_te_[out] = trace_te_[k];
      ++out;
      if (lo == hi) break;
    }
    i = end;
  }
  trace_t_.resize(out);
  trace_angle_.resize(out);
  trace_te_.resize(out);
  trace_stride_ *= 2;
}

DynamicTeResult DynamicTeRecord::finish(const GearTeeth& teeth,
                                        std::span<const PredictedComponent> predicted,
                                        const DynamicTeOptions& options) {
  if (block_count_ > 0) close_trace_block();
  if (kept_ < 8) {
    throw std::invalid_argument("dynamic TE: the record has " + std::to_string(kept_) +
                                " usable samples; expected at least 8");
  }
  DynamicRecordFigures figures;
  figures.samples = kept_;
  figures.duration_s = last_t_;
  figures.output_angle_rad = last_angle_;
  figures.input_angle_rad = std::abs(last_theta_in_ - theta_in_0_);
  figures.mean_arcsec = mean_;
  figures.p2p_arcsec = hi_ - lo_;
  figures.rms_arcsec = std::sqrt(m2_ / static_cast<double>(kept_));
  figures.second_difference_noise_arcsec =
      std::sqrt(second_ss_ / static_cast<double>(kept_ - 2) / 6.0);
  const RevolutionAverage averaged = welch_.finish();
  DynamicTeResult r =
      analyse_dynamic_record(figures, std::move(grid_), shape_.points_per_revolution, averaged,
                             sense_, teeth, predicted, options);
  r.time_s = std::move(trace_t_);
  r.output_angle_rad = std::move(trace_angle_);
  r.te_arcsec = std::move(trace_te_);
  r.trace_stride = trace_stride_;
  grid_.clear();
  return r;
}

}  // namespace wavebench::metrology
