#pragma once
// The mechanics behind the simulated bench: motor rotor + wave generator (J1), the gear's
// elastic twist with backlash and transmission error, and the output side (J2) with the brake.
// The gear's laws are the model's own objects (TeExcitation, BacklashDeadZone, the stiffness
// forms 1-7 with their memory, CoulombStribeck and LuGre on either shaft): one gear physics for
// the twin and the simulated unit. What is the plant's own is the time stepping: a fixed-step,
// semi-implicit scheme, causal, so that the devices can run it in real time or by SYNC ticks,
// and the brake as a set-valued friction (it holds the output, which GearModel's smooth brake
// law cannot).

#include <cstdint>
#include <variant>

#include "wavebench/model/backlash.hpp"
#include "wavebench/model/bouc_wen_spring.hpp"
#include "wavebench/model/coulomb_stribeck_friction.hpp"
#include "wavebench/model/elastic_stiffness.hpp"
#include "wavebench/model/fading_memory_spring.hpp"
#include "wavebench/model/gear_params.hpp"
#include "wavebench/model/hysteretic_branch_spring.hpp"
#include "wavebench/model/lugre_friction.hpp"
#include "wavebench/model/te_excitation.hpp"

namespace wavebench::simdevices {

struct PlantState {
  double t = 0;
  double theta_in = 0;           // theta1 [rad]
  double omega_in = 0;           // [rad/s]
  double theta_out = 0;          // theta2 [rad] in the model's convention
  double omega_out = 0;          // [rad/s]
  double twist = 0;              // Delta = theta1/N - theta2 - e [rad]
  double te = 0;                 // theta2 - theta1/N [rad]
  double gear_torque = 0;        // T_g at the output [N*m]
  double motor_torque = 0;       // T_m [N*m]
  double brake_torque = 0;       // torque the brake exerts on the output [N*m] (opposes motion)
  double shaft_torque = 0;       // torque through the sensor into brake and load [N*m]
  double friction_torque = 0;    // the gear's friction law's torque on its shaft [N*m]
  double output_travel_rad = 0;  // output angle turned either way since start (defect onsets)
};

// The state the model's laws carry between steps: the form-5 branch anchor and direction, the
// form-6 memory z or the form-7 hysteretic twist w, LuGre's bristle deflection.
struct PlantLawState {
  model::BranchAnchor anchor;
  double twist_direction = 1;  // sign of Delta' since the last reversal (form 5)
  double memory = 0;           // z [N*m] (form 6) or w [rad] (form 7)
  double bristle = 0;          // s [rad] (LuGre)
};

class SimulatedBenchPlant {
 public:
  // Throws std::invalid_argument naming the key when `params` cannot be simulated.
  explicit SimulatedBenchPlant(model::GearParams params, double max_substep = 2e-5);
  SimulatedBenchPlant(const SimulatedBenchPlant&) = delete;
  SimulatedBenchPlant& operator=(const SimulatedBenchPlant&) = delete;

  // Held constant over the next step() calls.
  void set_motor_torque(double torque_nm) noexcept { motor_torque_ = torque_nm; }
  // The brake's available torque [N*m, >= 0]: it holds the output up to it and slips above.
  void set_brake_torque(double torque_nm) noexcept { brake_limit_ = torque_nm < 0 ? 0 : torque_nm; }
  double brake_torque_setting() const noexcept { return brake_limit_; }

  void step(double dt);
  const PlantState& state() const noexcept { return state_; }
  const PlantLawState& law_state() const noexcept { return law_; }
  const model::GearParams& params() const noexcept { return params_; }
  double ratio() const noexcept { return ratio_; }
  double mesh_damping() const noexcept { return damping_; }

  // The gear's laws as the plant evaluates them, exposed for tests against the model's
  // functions and closed forms. The stiffness and friction use the law's current state.
  double te_excitation(double theta_in, double theta_out) const;
  double stiffness_torque(double x, double theta_in, double theta_out) const;  // K-term at x
  double backlash_filter(double twist) const;                                  // g(Delta)
  double friction_torque(double omega) const;  // on the shaft of params().friction_side

 private:
  using Spring = std::variant<model::ElasticStiffness, model::HystereticBranchSpring,
                              model::FadingMemorySpring, model::BoucWenSpring>;
  using Friction = std::variant<std::monostate, model::CoulombStribeck, model::LuGre>;

  void substep(double h);
  // Form 5's discrete dynamics at a step's end, as GearModel::on_event does at located events.
  void update_branch(double x, double x_rate, double spring, bool in_contact);

  model::GearParams params_;
  double ratio_ = 0;
  double damping_ = 0;
  double max_substep_;
  model::TeExcitation te_;
  model::BacklashDeadZone dead_zone_;
  Spring spring_;
  Friction friction_;
  bool output_friction_ = false;
  double motor_torque_ = 0;
  double brake_limit_ = 0;
  PlantState state_;
  PlantLawState law_;
};

}  // namespace wavebench::simdevices
