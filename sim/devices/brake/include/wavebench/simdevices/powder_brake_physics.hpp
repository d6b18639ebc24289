#pragma once
// Magnetic-powder brake (bench.md §3): the torque the powder can transmit follows the coil
// current with a first-order lag, along a different static curve when the current falls than
// when it rises; the brake holds the shaft up to that torque when the output stops and slips
// at that torque when it turns, and the slip power T·ω heats a lumped thermal mass.
//
// Static curve (rising): T = k·I for threshold ≤ I ≤ rated, k = rated_torque / rated_current;
// 0 below the threshold (the powder chains do not form); T saturates at the rated torque.
// Falling: magnetic remanence keeps the curve higher — a play operator of width `hysteresis_a`
// on the current: I_eff follows I upwards, and downwards only once I < I_eff − w, so on the
// falling branch T = curve(I + w).
// Lag: dT/dt = (T_ss − T)/τ with τ_rise when T_ss > T, τ_fall otherwise.
// Heat: C·dθ/dt = P_slip + R·I² − G·(θ − θ_ambient), P_slip = T·|ω| while slipping.
// step(dt) integrates all of it exactly for inputs held constant over dt, so the simulated
// clock can run at any rate.

namespace wavebench::simdevices {

struct PowderBrakeParams {
  double rated_current_a = 2.0;
  double rated_torque_nm = 100.0;
  double threshold_current_a = 0.05;
  double hysteresis_a = 0.04;
  double tau_rise_s = 0.08;
  double tau_fall_s = 0.15;
  double heat_capacity_j_per_k = 1500.0;
  double heat_loss_w_per_k = 3.0;
  double coil_resistance_ohm = 0.0;  // Joule heating of the coil; the spec heats by slip only
  double ambient_c = 25.0;
  // |ω| below this counts as stopped: the brake holds instead of slipping.
  double standstill_rad_per_s = 1e-3;
};

class PowderBrakePhysics {
 public:
  explicit PowderBrakePhysics(PowderBrakeParams params = {});

  // Coil current as the controller's current loop sets it (A, ≥ 0).
  void set_coil_current(double amps) noexcept;
  void set_coil_open(bool open) noexcept;
  void set_output_speed(double rad_per_s) noexcept { omega_ = rad_per_s; }
  void set_temperature(double celsius) noexcept { temperature_ = celsius; }

  void step(double dt) noexcept;

  double coil_current() const noexcept { return coil_open_ ? 0.0 : current_; }
  bool coil_open() const noexcept { return coil_open_; }
  double output_speed() const noexcept { return omega_; }
  // Torque the powder transmits at the moment (N·m, ≥ 0): the slip torque, and the most it
  // holds at standstill.
  double torque_capacity() const noexcept { return torque_; }
  // The steady-state torque the lag is heading for.
  double target_torque() const noexcept { return static_torque(effective_current_); }
  // Torque on the output shaft, opposing motion. At standstill it balances `driving_torque`
  // (the torque the gear applies) up to the capacity.
  double shaft_torque(double driving_torque) const noexcept;
  double slip_power() const noexcept;
  double temperature() const noexcept { return temperature_; }
  bool stopped() const noexcept;

  // Rising static curve T(I).
  double static_torque(double current) const noexcept;
  // Current the rising curve needs for torque T (the inverse of static_torque within range).
  double current_for_torque(double torque) const noexcept;
  // Current that brings the static torque to T from the present magnetic state: the rising
  // inverse when T is above the present curve, and below it the falling branch's inverse
  // (I = T/k − w), so a torque-mode controller lands on T from either side.
  double current_for_torque_from_here(double torque) const noexcept;
  const PowderBrakeParams& params() const noexcept { return params_; }

 private:
  PowderBrakeParams params_;
  double current_ = 0.0;
  double effective_current_ = 0.0;  // current after the hysteresis play operator
  double torque_ = 0.0;
  double omega_ = 0.0;
  double temperature_;
  bool coil_open_ = false;
};

}  // namespace wavebench::simdevices
