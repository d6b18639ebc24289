#include "wavebench/twin/measured_drive_twin.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>

#include "wavebench/model/gear_model.hpp"
#include "wavebench/model/solver/dormand_prince45.hpp"
#include "wavebench/model/solver/trajectory_runner.hpp"

namespace wavebench::twin {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kStartMarginRad = 1e-4;  // ~20 arcsec beyond the clearance
constexpr std::size_t kShortTorqueHalfWidth = 2;

// The gear model plus the measured load torque on the output: the model's own load is zero
// here, so the measured torque T enters as −T/J2 in ω2' and +T/J2 in the twist rate's rate
// (Δ-coordinates: q = θ1/N − θ2, q'' = α1/N − ω2'). Linear in time between two samples.
class MeasuredLoadSystem final : public model::solver::OdeSystem {
 public:
  MeasuredLoadSystem(const model::GearModel& model, double inertia_output,
                     std::span<const double> scale)
      : model_(model),
        inv_j2_(1.0 / inertia_output),
        twist_rate_(static_cast<std::size_t>(model.layout().twist_rate)),
        scale_(scale) {}

  void set_interval(double t0, double load0, double t1, double load1) {
    t0_ = t0;
    load0_ = load0;
    slope_ = t1 > t0 ? (load1 - load0) / (t1 - t0) : 0.0;
  }

  std::size_t continuous_size() const override { return model_.continuous_size(); }
  std::size_t discrete_size() const override { return model_.discrete_size(); }
  void derivatives(double t, std::span<const double> y, std::span<const double> d,
                   std::span<double> dydt) const override {
    model_.derivatives(t, y, d, dydt);
    dydt[twist_rate_] += (load0_ + slope_ * (t - t0_)) * inv_j2_;
  }
  void error_scale(std::span<double> scale) const override {
    std::copy(scale_.begin(), scale_.end(), scale.begin());
  }
  std::size_t witness_count() const override { return model_.witness_count(); }
  void witnesses(double t, std::span<const double> y, std::span<const double> d,
                 std::span<double> g) const override {
    model_.witnesses(t, y, d, g);
  }
  void on_event(std::size_t witness, double t, std::span<double> y,
                std::span<double> d) const override {
    model_.on_event(witness, t, y, d);
  }

 private:
  const model::GearModel& model_;
  double inv_j2_;
  std::size_t twist_rate_;
  std::span<const double> scale_;
  double t0_ = 0, load0_ = 0, slope_ = 0;
};

struct DrivePoint {
  double t = 0;           // [s] since the first driving sample
  double theta1 = 0;      // [rad] as it drives the model (smoothed)
  double theta1_raw = 0;  // [rad] as measured
  double load = 0;        // [N·m] on the output, model direction
  std::size_t point = 0;
};

// Centred Savitzky–Golay weights, quadratic fit over 2m + 1 evenly spaced points.
std::vector<double> savitzky_golay_weights(int m) {
  std::vector<double> w;
  const double den = (2.0 * m + 1) * (4.0 * m * m + 4.0 * m - 3);
  for (int j = -m; j <= m; ++j)
    w.push_back((3.0 * (3.0 * m * m + 3.0 * m - 1) - 15.0 * j * j) / den);
  return w;
}

}  // namespace

model::GearParams measured_drive_params(const model::GearParams& nominal) {
  model::GearParams p = nominal;
  p.input = model::KinematicInput{};
  p.friction = model::NoFriction{};
  p.load.brake.reset();
  p.load.output_torque = {};
  p.load.drive_ripple = {};
  p.nominal_input_speed = 0;
  return p;
}

TwinSampleInput twin_input(const storage::SyncSample& s) {
  return {s.index, s.receive_time_ns, s.flags, s.theta_in_rad, s.theta_out_rad, s.torque_nm};
}

struct MeasuredDriveTwin::Impl {
  model::GearParams params;
  metrology::GearSense sense;
  TwinSolverOptions options;
  model::solver::DormandPrince45 integrator;
  // The points not yet taken (take_settled_points): points[k] is point points_front + k.
  std::deque<TwinPoint> points;
  std::size_t points_front = 0;
  bool flushed = false;
  TwinPoint& point(std::size_t i) { return points[i - points_front]; }
  std::size_t half_width = 0;  // look-ahead: the longer of the two windows
  std::size_t angle_half_width = 0;
  std::vector<double> weights;
  std::size_t torque_half_width = 0;
  std::vector<double> torque_weights, short_weights;
  double disagreement_gain = 0;  // RMS gain of (long − short window) on white noise
  double torque_noise_squares = 0;
  std::uint64_t torque_noise_count = 0;
  std::deque<DrivePoint> raw;  // measured drive waiting for its smoothing window
  std::uint64_t raw_front = 0, next_emit = 0;
  std::deque<DrivePoint> drive;
  std::size_t integrated = 0;  // drive[integrated] is the last point the twin has reached
  bool started = false;
  double t_origin = 0;
  double last_load = 0;
  double next_step = 0;
  std::vector<double> y, d, scale;
  std::uint64_t predicted = 0;
  std::int64_t steps = 0;

  Impl(const model::GearParams& gear, const metrology::GearSense& s, TwinSolverOptions o)
      : params(measured_drive_params(gear)),
        sense(s),
        options(o),
        integrator(model::solver::StepControl{{o.rtol, o.atol}, o.max_step, 0.0}),
        half_width(static_cast<std::size_t>(
            std::max({0, o.smoothing_half_width, o.torque_smoothing_half_width}))),
        angle_half_width(static_cast<std::size_t>(std::max(0, o.smoothing_half_width))),
        weights(savitzky_golay_weights(std::max(1, o.smoothing_half_width))),
        torque_half_width(static_cast<std::size_t>(std::max(0, o.torque_smoothing_half_width))),
        torque_weights(savitzky_golay_weights(std::max(1, o.torque_smoothing_half_width))),
        short_weights(savitzky_golay_weights(static_cast<int>(std::min<std::size_t>(
            kShortTorqueHalfWidth, std::max<std::size_t>(1, torque_half_width))))) {
    // (w_long − w_short) aligned on the centre.
    const std::size_t kl = torque_weights.size() / 2, ks = short_weights.size() / 2;
    double g = 0;
    for (std::size_t j = 0; j < torque_weights.size(); ++j) {
      double w = torque_weights[j];
      if (j + ks >= kl && j <= kl + ks) w -= short_weights[j + ks - kl];
      g += w * w;
    }
    disagreement_gain = std::sqrt(g);
  }

  model::GearParams params_over(std::size_t first, std::size_t last) const {
    model::GearParams p = params;
    auto& k = std::get<model::KinematicInput>(p.input);
    if (first == last) {  // one sample: standing still there
      k.trace_t = {drive[first].t, drive[first].t + 1.0};
      k.trace_theta = {drive[first].theta1, drive[first].theta1};
      return p;
    }
    for (std::size_t i = first; i <= last; ++i) {
      k.trace_t.push_back(drive[i].t);
      k.trace_theta.push_back(drive[i].theta1);
    }
    return p;
  }

  void record(const model::GearModel& model, std::size_t i) {
    const model::GearOutputs o = model.outputs(drive[i].t, y, d);
    TwinPoint& p = point(drive[i].point);
    // The model's TE is against the θ1 that drove it; the measurement's against θ_in.
    p.predicted_te_rad = o.te + (drive[i].theta1 - drive[i].theta1_raw) / model.ratio() +
                         options.input_latch_delay_s * o.omega1 / model.ratio();
    p.omega1_rad_s = o.omega1;
    p.excitation_rad = o.te_excitation;
    p.spring_twist_rad = o.spring_twist;
    p.twist_rad = o.twist;
    p.omega2_rad_s = o.omega2;
    p.gear_torque_nm = o.gear_torque;
    ++predicted;
  }

  void start(std::size_t last) {
    model::GearParams p = params_over(0, last);
    p.load.output_torque.offset = drive[0].load;  // the steady twist carries the first load
    const model::GearModel preload(p, true);
    y = preload.initial_state();
    d = preload.initial_discrete();
    scale.assign(y.size(), 1.0);
    preload.error_scale(scale);
    // Start from the measured output when it is where the gear can be (within the clearance
    // of the model's steady state, plus a margin): at rest inside the backlash only the
    // measurement knows where the output floats. An encoder zero offset (any size on a real
    // bench) would otherwise become a twist; the calibration fits it as a TE offset.
    const double te0 = point(drive[0].point).measured_te_rad;
    const auto twist = static_cast<std::size_t>(preload.layout().twist);
    if (options.start_from_measured_output && std::isfinite(te0)) {
      // q = θ1/N − θ2 with θ2 as measured: θ2 = TE + θ_in/N.
      const double q = -te0 + (drive[0].theta1 - drive[0].theta1_raw) / preload.ratio();
      const double margin = 0.5 * params.backlash.total_rad + kStartMarginRad;
      if (std::abs(q - y[twist]) <= margin) y[twist] = q;
    }
    // The output follows the TE lines below its own mode and not those above (the mesh): start
    // it so, else it rings at the mode from the first sample (the model's initial state has
    // the output following every line).
    {
      const model::GearOutputs o = preload.outputs(drive[0].t, y, d);
      const double omega_n = std::sqrt(preload.mean_stiffness() / params.inertia_output);
      double rate = 0;
      for (const auto& term : params.te_terms) {
        const double w =
            term.order_input * o.omega1 + term.order_output * o.omega1 / preload.ratio();
        if (std::abs(w) >= omega_n) continue;
        rate += term.amplitude_rad * w *
                std::cos(term.order_input * o.theta1 +
                         term.order_output * (o.theta1 / preload.ratio() + o.te) + term.phase_rad);
      }
      y[static_cast<std::size_t>(preload.layout().twist_rate)] = rate;
    }
    p.load.output_torque.offset = 0;
    const model::GearModel model(p, true);
    record(model, 0);
    integrated = 0;
    started = true;
  }

  // Integrates from drive[integrated] to drive[to] with the trace drive[first..last].
  void integrate(std::size_t to, std::size_t first, std::size_t last) {
    const model::GearModel model(params_over(first, last), true);
    MeasuredLoadSystem system(model, params.inertia_output, scale);
    for (std::size_t i = integrated; i < to; ++i) {
      const DrivePoint& a = drive[i];
      const DrivePoint& b = drive[i + 1];
      system.set_interval(a.t, a.load, b.t, b.load);
      model::solver::TrajectoryOptions o;
      o.t_end = b.t;
      o.initial_step = next_step > 0 ? std::min(next_step, b.t - a.t) : 0.0;
      model::solver::TrajectoryRunner runner(integrator, system, o);
      const auto result = runner.run(a.t, y, d);
      steps += result.counters.steps;
      next_step = integrator.proposed_step();
      record(model, i + 1);
    }
    integrated = to;
  }

  void advance(bool final) {
    if (drive.empty()) return;
    std::size_t last = drive.size() - 1;
    if (!started) {
      if (!final && drive.size() < 4) return;
      start(last);
    }
    const std::size_t first = integrated > 0 ? integrated - 1 : 0;
    const std::size_t to = final ? last : last - 1;
    // The trace needs four points for PCHIP; its slopes at drive[integrated..to] then depend
    // only on their neighbours, so chunk boundaries leave no seam.
    if (to > integrated && (final || last - first + 1 >= 4)) integrate(to, first, last);
    // Keep the point before the one reached: the next trace needs it for its first slope.
    while (integrated > 1) {
      drive.pop_front();
      --integrated;
    }
  }

  void push(const TwinSampleInput& s) {
    TwinPoint p;
    p.index = s.index;
    p.t_s = static_cast<double>(s.time_ns) * 1e-9;
    const bool in_ok = (s.flags & storage::kThetaInValid) != 0;
    const bool out_ok = (s.flags & storage::kThetaOutValid) != 0;
    p.theta1_rad = in_ok ? s.theta_in_rad : kNaN;
    p.theta2_rad = out_ok ? sense.model_output_angle(s.theta_out_rad) : kNaN;
    p.measured_te_rad =
        in_ok && out_ok ? sense.transmission_error(s.theta_in_rad, s.theta_out_rad) : kNaN;
    p.predicted_te_rad = p.excitation_rad = p.spring_twist_rad = p.twist_rad = kNaN;
    p.omega1_rad_s = p.omega2_rad_s = p.gear_torque_nm = kNaN;
    points.push_back(p);
    if (!in_ok) return;  // the twin is driven by θ_in: a sample without it is skipped
    // A missing torque holds the last one; the sensor's sign maps onto the model's direction.
    if ((s.flags & storage::kTorqueValid) != 0) last_load = sense.direction_sign * s.torque_nm;
    if (raw.empty() && next_emit == 0) t_origin = p.t_s;
    double t = p.t_s - t_origin;
    if (!raw.empty() && !(t > raw.back().t)) t = raw.back().t + 1e-7;
    raw.push_back({t, s.theta_in_rad, s.theta_in_rad, last_load, points_front + points.size() - 1});
    observe_torque_noise();
    while (next_emit + half_width < raw_front + raw.size()) emit(false);
    advance(false);
  }

  // The torque over the long window where it is a quadratic trend plus noise; where the long
  // and the short window disagree beyond the noise (a holding brake turning over at a
  // reversal), over the short one.
  double smoothed_load(std::size_t c) const {
    const std::size_t kt = torque_half_width;
    if (kt == 0) return raw[c].load;
    double longer = 0;
    for (std::size_t j = 0; j <= 2 * kt; ++j) longer += torque_weights[j] * raw[c - kt + j].load;
    const std::size_t ks = std::min<std::size_t>(kShortTorqueHalfWidth, kt);
    double shorter = 0;
    for (std::size_t j = 0; j <= 2 * ks; ++j) shorter += short_weights[j] * raw[c - ks + j].load;
    if (torque_noise_count < 20) return shorter;
    const double sigma = std::sqrt(torque_noise_squares / (20.0 * torque_noise_count));
    return std::abs(longer - shorter) <= 4 * sigma * disagreement_gain ? longer : shorter;
  }

  // Running estimate of the torque noise from third differences, outliers (steps) left out.
  void observe_torque_noise() {
    const std::size_t n = raw.size();
    if (n < 4) return;
    const double d3 = raw[n - 1].load - 3 * raw[n - 2].load + 3 * raw[n - 3].load - raw[n - 4].load;
    const double mean = torque_noise_count > 0 ? torque_noise_squares / torque_noise_count : 0;
    if (torque_noise_count >= 20 && d3 * d3 > 25 * mean) return;
    torque_noise_squares += d3 * d3;
    ++torque_noise_count;
  }

  // Moves the next raw sample to the drive, smoothed when its window is complete and even.
  void emit(bool raw_only) {
    const std::size_t c = static_cast<std::size_t>(next_emit - raw_front);
    DrivePoint out = raw[c];
    const std::size_t k = half_width;
    if (!raw_only && k > 0 && c >= k && c + k < raw.size()) {
      const double h = (raw[c + k].t - raw[c - k].t) / static_cast<double>(2 * k);
      bool even = true;
      for (std::size_t j = c - k + 1; j <= c + k; ++j) {
        even = even && std::abs(raw[j].t - raw[j - 1].t - h) <= 0.2 * h;
      }
      if (even) {
        const std::size_t ka = angle_half_width;
        double theta = 0;
        for (std::size_t j = 0; ka > 0 && j <= 2 * ka; ++j) {
          // Relative to the centre: the weights sum to 1, and an angle of many turns keeps
          // its last digits.
          theta += weights[j] * (raw[c - ka + j].theta1 - out.theta1_raw);
        }
        out.theta1 = out.theta1_raw + theta;
        out.load = smoothed_load(c);
      }
    }
    drive.push_back(out);
    ++next_emit;
    while (raw_front + k < next_emit && !raw.empty()) {
      raw.pop_front();
      ++raw_front;
    }
  }

  void flush() {
    while (next_emit < raw_front + raw.size()) emit(true);
    advance(true);
    flushed = true;
  }

  // Points before this one change no more: predicted up to the sample the twin reached, or
  // never predicted (no input angle).
  std::size_t settled_end() const {
    if (flushed) return points_front + points.size();
    if (!started || drive.empty()) return points_front;
    return drive[integrated].point + 1;
  }
};

MeasuredDriveTwin::MeasuredDriveTwin(const model::GearParams& gear,
                                     const metrology::GearSense& sense,
                                     TwinSolverOptions options) {
  sense.validate();
  impl_ = std::make_unique<Impl>(gear, sense, options);
  // Validate the gear now, on the caller's thread, with a trivial trace.
  model::GearParams probe = impl_->params;
  std::get<model::KinematicInput>(probe.input).trace_t = {0.0, 1.0};
  std::get<model::KinematicInput>(probe.input).trace_theta = {0.0, 0.0};
  const model::GearModel model(probe, true);
  if (std::abs(model.ratio() - sense.ratio) > 1e-9 * sense.ratio) {
    throw std::invalid_argument("twin gear '" + gear.name + "' has ratio " +
                                std::to_string(model.ratio()) + ", the bench's gear " +
                                std::to_string(sense.ratio) + "; expected the same ratio");
  }
}

MeasuredDriveTwin::~MeasuredDriveTwin() = default;

void MeasuredDriveTwin::push(const TwinSampleInput& sample) {
  impl_->push(sample);
}
void MeasuredDriveTwin::flush() {
  impl_->flush();
}
std::size_t MeasuredDriveTwin::take_settled_points(std::vector<TwinPoint>& out) {
  auto& im = *impl_;
  const std::size_t n = std::min(im.points.size(), im.settled_end() - im.points_front);
  out.insert(out.end(), std::make_move_iterator(im.points.begin()),
             std::make_move_iterator(im.points.begin() + static_cast<std::ptrdiff_t>(n)));
  im.points.erase(im.points.begin(), im.points.begin() + static_cast<std::ptrdiff_t>(n));
  im.points_front += n;
  return n;
}
std::vector<TwinPoint> MeasuredDriveTwin::take_points() {
  auto& im = *impl_;
  std::vector<TwinPoint> out(std::make_move_iterator(im.points.begin()),
                             std::make_move_iterator(im.points.end()));
  im.points_front += im.points.size();
  im.points.clear();
  return out;
}
bool MeasuredDriveTwin::started() const {
  return impl_->started;
}
double MeasuredDriveTwin::twin_time_s() const {
  if (!impl_->started || impl_->drive.empty()) return kNaN;
  return impl_->t_origin + impl_->drive[impl_->integrated].t;
}
std::uint64_t MeasuredDriveTwin::predicted() const {
  return impl_->predicted;
}
std::int64_t MeasuredDriveTwin::solver_steps() const {
  return impl_->steps;
}

std::vector<TwinPoint> replay_twin(const model::GearParams& gear,
                                   const metrology::GearSense& sense,
                                   std::span<const storage::SyncSample> samples,
                                   TwinSolverOptions options) {
  MeasuredDriveTwin twin(gear, sense, options);
  for (const auto& s : samples) twin.push(twin_input(s));
  twin.flush();
  return twin.take_points();
}

}  // namespace wavebench::twin
