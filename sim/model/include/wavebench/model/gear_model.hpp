#pragma once
// The two-inertia strain-wave gear (model.md §2) as an OdeSystem. It holds only parameters and
// the laws built from them; the state lives with the integrator. Integrated in deviation
// coordinates (model.md §8) so tolerances act on arcsecond-sized quantities.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "wavebench/model/backlash.hpp"
#include "wavebench/model/bouc_wen_spring.hpp"
#include "wavebench/model/coulomb_stribeck_friction.hpp"
#include "wavebench/model/dc_motor.hpp"
#include "wavebench/model/elastic_stiffness.hpp"
#include "wavebench/model/fading_memory_spring.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/hysteretic_branch_spring.hpp"
#include "wavebench/model/kinematic_motion.hpp"
#include "wavebench/model/lugre_friction.hpp"
#include "wavebench/model/powder_brake.hpp"
#include "wavebench/model/servo_drive.hpp"
#include "wavebench/model/solver/ode_system.hpp"
#include "wavebench/model/state_layout.hpp"
#include "wavebench/model/te_excitation.hpp"

namespace wavebench::model {

// Everything derived from one state, for sampling and checks.
struct GearOutputs {
  double theta1 = 0, omega1 = 0, alpha1 = 0;
  double theta2_dev = 0;  // theta2 - theta1_nominal(t)/N
  double omega2 = 0, alpha2 = 0;
  double te_excitation = 0, te_excitation_rate = 0;  // e, e'
  double twist = 0, twist_rate = 0;                  // Delta, Delta'
  double spring_twist = 0;                           // x = g(Delta)
  double te = 0;                                     // theta2 - theta1/N
  double spring_torque = 0;                          // K-term
  double gear_torque = 0;                            // T_g
  double load_torque = 0, motor_torque = 0, friction_torque = 0;
  double loss_power = 0;  // mesh damping + hysteresis + friction + viscous + drag [W]
};

class GearModel final : public solver::OdeSystem {
 public:
  // Throws std::invalid_argument naming the parameter, its value and what was expected.
  explicit GearModel(const GearParams& params, bool locate_events = true);

  const StateLayout& layout() const noexcept { return layout_; }
  double ratio() const noexcept { return ratio_; }
  double mean_stiffness() const noexcept { return mean_stiffness_; }
  double mesh_damping() const noexcept { return damping_; }
  double equivalent_inertia() const noexcept { return j_eq_; }
  double reference_speed() const noexcept { return omega_ref_; }

  // Start: at the reference speed, twisted to carry the mean output load, Delta' = 0.
  std::vector<double> initial_state() const;
  std::vector<double> initial_discrete() const;

  GearOutputs outputs(double t, std::span<const double> y, std::span<const double> d) const;
  // "contact_made", "contact_lost", "reversal" or "zero_torque".
  std::string event_kind(std::size_t witness, int direction) const;

  std::size_t continuous_size() const override { return layout_.size; }
  std::size_t discrete_size() const override { return layout_.discrete_size; }
  void derivatives(double t, std::span<const double> y, std::span<const double> d,
                   std::span<double> dydt) const override;
  void error_scale(std::span<double> scale) const override;
  std::size_t witness_count() const override { return layout_.witness_count; }
  void witnesses(double t, std::span<const double> y, std::span<const double> d,
                 std::span<double> g) const override;
  void on_event(std::size_t witness, double t, std::span<double> y,
                std::span<double> d) const override;

 private:
  struct TorqueDrive {
    Sinusoid torque;
  };
  using Drive = std::variant<TorqueDrive, DcMotor, ServoDrive, KinematicMotion>;
  using Friction = std::variant<std::monostate, CoulombStribeck, LuGre>;
  using Spring =
      std::variant<ElasticStiffness, HystereticBranchSpring, FadingMemorySpring, BoucWenSpring>;

  struct MeshMotion {
    double theta1 = 0, omega1 = 0, alpha1 = 0, u1 = 0, q = 0, r = 0, theta2 = 0, omega2 = 0;
    TeValue e;
    double delta = 0, delta_rate = 0;
  };
  // The shaft motions, the TE excitation and the twist: what the witnesses need.
  MeshMotion mesh_motion(double t, const double* y) const noexcept;
  // One evaluation of the whole model; dydt and out may be null.
  void evaluate(double t, const double* y, const double* d, double* dydt, GearOutputs* out) const;
  double preload_twist(double torque) const;

  GearParams params_;
  StateLayout layout_;
  double ratio_ = 0, inv_ratio_ = 0, j1_ = 0, j2_ = 0, omega_ref_ = 0;
  double mean_stiffness_ = 0, damping_ = 0, j_eq_ = 0;
  double fastest_line_ = 0;  // [rad/s] fastest TE or stiffness line at the nominal speed
  TeExcitation te_;
  BacklashDeadZone dead_zone_;
  Spring spring_;
  Friction friction_;
  Drive drive_;
  std::optional<PowderBrake> brake_;
  bool kinematic_ = false;
};

}  // namespace wavebench::model
