// The inverse of twin_case.cpp: every field the parsers read, written under the same keys.
#include "wavebench/config/twin_case_writer.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <sstream>
#include <variant>

namespace wavebench::config {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Clang before 17 does not deduce aggregate bases without it (the fuzz build uses clang).
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// A plain number is SI to the loader; 17 digits make the round trip exact.
std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void key_number(YAML::Emitter& out, const char* key, double v) {
  out << YAML::Key << key << YAML::Value << number(v);
}

void numbers(YAML::Emitter& out, const char* key, const std::vector<double>& values) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (double v : values) out << number(v);
  out << YAML::EndSeq;
}

void sinusoid(YAML::Emitter& out, const char* key, const model::Sinusoid& s) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  key_number(out, "offset", s.offset);
  key_number(out, "amplitude", s.amplitude);
  key_number(out, "frequency", s.frequency_hz);
  key_number(out, "phase", s.phase_rad);
  out << YAML::EndMap;
}

void harmonics(YAML::Emitter& out, const char* key,
               const std::vector<model::StiffnessHarmonic>& list) {
  out << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const auto& h : list) {
    out << YAML::Flow << YAML::BeginMap;
    key_number(out, "amplitude", h.amplitude);
    key_number(out, "order_input", h.order_input);
    key_number(out, "order_output", h.order_output);
    key_number(out, "phase", h.phase_rad);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void gear_section(YAML::Emitter& out, const model::GearParams& g) {
  out << YAML::Key << "gear" << YAML::Value << YAML::BeginMap;
  if (g.geometry.z_flex > 0 && g.geometry.z_circ > g.geometry.z_flex) {
    out << YAML::Key << "z_flex" << YAML::Value << g.geometry.z_flex;
    out << YAML::Key << "z_circ" << YAML::Value << g.geometry.z_circ;
  }
  if (g.geometry.ratio > 0) key_number(out, "ratio", g.geometry.ratio);
  out << YAML::Key << "wave_number" << YAML::Value << g.geometry.wave_number;
  out << YAML::Key << "direction" << YAML::Value << g.geometry.direction_sign;
  key_number(out, "inertia_input", g.inertia_input);
  key_number(out, "inertia_output", g.inertia_output);
  key_number(out, "viscous_input", g.viscous_input);
  key_number(out, "viscous_output", g.viscous_output);
  out << YAML::EndMap;
}

void te_section(YAML::Emitter& out, const model::GearParams& g) {
  if (g.te_terms.empty()) return;
  out << YAML::Key << "te" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "terms" << YAML::Value << YAML::BeginSeq;
  for (const auto& t : g.te_terms) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "source" << YAML::Value << t.source;
    out << YAML::Key << "family" << YAML::Value << te_family_name(t.family);
    if (t.family == model::TeFamily::kCustom) {
      key_number(out, "order_input", t.order_input);
      key_number(out, "order_output", t.order_output);
    }
    key_number(out, "amplitude", t.amplitude_rad);
    key_number(out, "phase", t.phase_rad);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

void stiffness_section(YAML::Emitter& out, const model::StiffnessParams& s) {
  out << YAML::Key << "stiffness" << YAML::Value << YAML::BeginMap;
  std::visit(
      Overloaded{[&](const model::LinearPeriodicStiffness& l) {
                   out << YAML::Key << "form" << YAML::Value << "linear_periodic";
                   key_number(out, "k0", l.k0);
                   if (!l.harmonics.empty()) harmonics(out, "harmonics", l.harmonics);
                 },
                 [&](const model::CubicStiffness& c) {
                   out << YAML::Key << "form" << YAML::Value << "cubic";
                   key_number(out, "k1", c.k1);
                   key_number(out, "k3", c.k3);
                 },
                 [&](const model::ThreeSegmentStiffness& c) {
                   out << YAML::Key << "form" << YAML::Value << "three_segment";
                   key_number(out, "k1", c.k1);
                   key_number(out, "t1", c.t1);
                   key_number(out, "k2", c.k2);
                   key_number(out, "t2", c.t2);
                   key_number(out, "k3", c.k3);
                 },
                 [&](const model::TableStiffness& t) {
                   out << YAML::Key << "form" << YAML::Value << "table";
                   numbers(out, "twist", t.twist_rad);
                   numbers(out, "torque", t.torque_nm);
                 },
                 [&](const model::HystereticBranchStiffness& h) {
                   out << YAML::Key << "form" << YAML::Value << "hysteretic_branches";
                   out << YAML::Key << "loading" << YAML::Value << YAML::Flow << YAML::BeginMap;
                   key_number(out, "a", h.a_load);
                   key_number(out, "b", h.b_load);
                   key_number(out, "c", h.c_load);
                   out << YAML::EndMap;
                   out << YAML::Key << "unloading" << YAML::Value << YAML::Flow << YAML::BeginMap;
                   key_number(out, "a", h.a_unload);
                   key_number(out, "b", h.b_unload);
                   key_number(out, "c", h.c_unload);
                   out << YAML::EndMap;
                 },
                 [&](const model::FadingMemoryStiffness& f) {
                   out << YAML::Key << "form" << YAML::Value << "fading_memory";
                   key_number(out, "a", f.a);
                   key_number(out, "b", f.b);
                   key_number(out, "c", f.c);
                   key_number(out, "memory_gain", f.memory_gain);
                   key_number(out, "memory_decay", f.memory_decay);
                 },
                 [&](const model::BoucWenStiffness& b) {
                   out << YAML::Key << "form" << YAML::Value << "bouc_wen";
                   key_number(out, "k", b.k);
                   key_number(out, "alpha", b.alpha);
                   key_number(out, "beta", b.beta);
                   key_number(out, "gamma", b.gamma);
                   key_number(out, "n", b.n);
                 }},
      s.law);
  if (!s.modulation.empty()) harmonics(out, "modulation", s.modulation);
  if (s.mean_stiffness) key_number(out, "mean", *s.mean_stiffness);
  out << YAML::EndMap;
}

void friction_section(YAML::Emitter& out, const model::FrictionLaw& friction,
                      model::FrictionSide side) {
  out << YAML::Key << "friction" << YAML::Value << YAML::BeginMap;
  if (side == model::FrictionSide::kOutput) out << YAML::Key << "side" << YAML::Value << "output";
  std::visit(Overloaded{[&](const model::NoFriction&) {
                          out << YAML::Key << "model" << YAML::Value << "none";
                        },
                        [&](const model::CoulombStribeckFriction& f) {
                          out << YAML::Key << "model" << YAML::Value << "coulomb_stribeck";
                          key_number(out, "coulomb", f.coulomb);
                          key_number(out, "static", f.static_torque);
                          key_number(out, "stribeck_speed", f.stribeck_speed);
                          key_number(out, "viscous", f.viscous);
                          key_number(out, "smoothing_speed", f.smoothing_speed);
                        },
                        [&](const model::LuGreFriction& f) {
                          out << YAML::Key << "model" << YAML::Value << "lugre";
                          key_number(out, "sigma0", f.sigma0);
                          key_number(out, "sigma1", f.sigma1);
                          key_number(out, "sigma2", f.sigma2);
                          key_number(out, "coulomb", f.coulomb);
                          key_number(out, "static", f.static_torque);
                          key_number(out, "stribeck_speed", f.stribeck_speed);
                        }},
             friction);
  out << YAML::EndMap;
}

void input_section(YAML::Emitter& out, const model::GearParams& g) {
  out << YAML::Key << "input" << YAML::Value << YAML::BeginMap;
  std::visit(Overloaded{[&](const model::TorqueInput& t) {
                          out << YAML::Key << "type" << YAML::Value << "torque";
                          sinusoid(out, "torque", t.torque);
                        },
                        [&](const model::DcMotorInput& m) {
                          out << YAML::Key << "type" << YAML::Value << "dc_motor";
                          key_number(out, "resistance", m.resistance);
                          key_number(out, "inductance", m.inductance);
                          key_number(out, "torque_constant", m.torque_constant);
                          key_number(out, "back_emf_constant", m.back_emf_constant);
                          key_number(out, "no_load_torque", m.no_load_torque);
                          sinusoid(out, "voltage", m.voltage);
                        },
                        [&](const model::ServoDriveInput& d) {
                          out << YAML::Key << "type" << YAML::Value << "servo";
                          out << YAML::Key << "position_control" << YAML::Value
                              << d.position_control;
                          key_number(out, "position_gain", d.position_gain);
                          key_number(out, "velocity_gain", d.velocity_gain);
                          key_number(out, "velocity_integral_time", d.velocity_integral_time);
                          key_number(out, "torque_limit", d.torque_limit);
                          key_number(out, "speed_limit", d.speed_limit);
                          key_number(out, "speed_setpoint", d.speed_setpoint);
                          key_number(out, "position_setpoint", d.position_setpoint);
                        },
                        [&](const model::KinematicInput& k) {
                          out << YAML::Key << "type" << YAML::Value << "kinematic";
                          key_number(out, "speed", k.speed);
                          key_number(out, "ramp_time", k.ramp_time);
                          if (!k.trace_t.empty()) {
                            out << YAML::Key << "trace" << YAML::Value << YAML::BeginMap;
                            numbers(out, "t", k.trace_t);
                            numbers(out, "theta", k.trace_theta);
                            out << YAML::EndMap;
                          }
                        }},
             g.input);
  key_number(out, "nominal_speed", g.nominal_input_speed);
  out << YAML::EndMap;
}

void load_section(YAML::Emitter& out, const model::LoadParams& l) {
  out << YAML::Key << "load" << YAML::Value << YAML::BeginMap;
  sinusoid(out, "output_torque", l.output_torque);
  sinusoid(out, "drive_ripple", l.drive_ripple);
  key_number(out, "output_drag", l.output_drag_coulomb);
  key_number(out, "drag_smoothing_speed", l.drag_smoothing_speed);
  if (l.brake) {
    const auto& b = *l.brake;
    out << YAML::Key << "brake" << YAML::Value << YAML::BeginMap;
    key_number(out, "rated_current", b.rated_current_a);
    key_number(out, "rated_torque", b.rated_torque_nm);
    key_number(out, "threshold_current", b.threshold_current_a);
    key_number(out, "hysteresis", b.hysteresis_a);
    key_number(out, "tau_rise", b.tau_rise_s);
    key_number(out, "tau_fall", b.tau_fall_s);
    key_number(out, "current", l.brake_current_a);
    key_number(out, "standstill_speed", b.standstill_rad_per_s);
    key_number(out, "thermal_capacity", b.heat_capacity_j_per_k);
    // The config's form of the heat loss (K/W); no thermal model without a capacity.
    if (b.heat_capacity_j_per_k > 0 && b.heat_loss_w_per_k > 0) {
      key_number(out, "thermal_resistance", 1 / b.heat_loss_w_per_k);
    }
    key_number(out, "ambient_temperature", b.ambient_c);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void solver_section(YAML::Emitter& out, const model::SimulationOptions& s) {
  out << YAML::Key << "solver" << YAML::Value << YAML::BeginMap;
  const char* method = s.method == model::SolverMethod::kRk4           ? "rk4"
                       : s.method == model::SolverMethod::kRosenbrock4 ? "rosenbrock"
                                                                       : "dopri5";
  out << YAML::Key << "method" << YAML::Value << method;
  key_number(out, "rtol", s.rtol);
  key_number(out, "atol", s.atol);
  key_number(out, "t_end", s.t_end);
  key_number(out, "transient", s.transient);
  key_number(out, "sample_rate", s.sample_rate);
  key_number(out, "fixed_step", s.fixed_step);
  key_number(out, "max_step", s.max_step);
  out << YAML::Key << "locate_events" << YAML::Value << s.locate_events;
  out << YAML::EndMap;
}

}  // namespace

std::string write_twin_case_yaml(const TwinCase& twin, const std::string& comment) {
  const model::GearParams& g = twin.gear;
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << g.name;
  gear_section(out, g);
  te_section(out, g);
  stiffness_section(out, g.stiffness);
  out << YAML::Key << "backlash" << YAML::Value << YAML::BeginMap;
  key_number(out, "total", g.backlash.total_rad);
  key_number(out, "smoothing", g.backlash.smoothing_rad);
  out << YAML::EndMap;
  if (g.damping.coefficient || g.damping.damping_ratio) {
    out << YAML::Key << "damping" << YAML::Value << YAML::BeginMap;
    if (g.damping.coefficient) {
      key_number(out, "coefficient", *g.damping.coefficient);
    } else {
      key_number(out, "ratio", *g.damping.damping_ratio);
    }
    out << YAML::EndMap;
  }
  friction_section(out, g.friction, g.friction_side);
  input_section(out, g);
  load_section(out, g.load);
  solver_section(out, twin.solver);
  out << YAML::EndMap;

  std::ostringstream text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text << "# " << line << "\n";
  text
      << "# Values are SI (rad, s, N*m, kg*m^2, N*m/rad); configs/twin/README.md has the schema.\n";
  text << out.c_str() << "\n";
  return text.str();
}

const char* te_family_name(model::TeFamily f) {
  switch (f) {
    case model::TeFamily::kWaveGenerator:
      return "wave_generator";
    case model::TeFamily::kHousing:
      return "housing";
    case model::TeFamily::kTangentialOutput:
      return "tangential_output";
    case model::TeFamily::kTangentialFixed:
      return "tangential_fixed";
    case model::TeFamily::kOutputAssembly:
      return "output_assembly";
    case model::TeFamily::kToothMesh:
      return "tooth_mesh";
    case model::TeFamily::kOutputOnceRev:
      return "output_once_rev";
    case model::TeFamily::kCustom:
      break;
  }
  return "custom";
}

}  // namespace wavebench::config
