#pragma once
// Where each state of the gear model lives in the continuous vector y and the discrete vector d.
// Computed once from the parameters; an index of -1 means the state does not exist for them.
#include <cstddef>

namespace wavebench::model {

struct StateLayout {
  // Continuous, in deviation coordinates (model.md §8).
  int input_angle = -1;        // u1 = theta1 - Omega_ref t (absent for a kinematic input)
  int input_speed = -1;        // v1 = omega1 - Omega_ref
  int twist = -1;              // q = theta1/N - theta2 (the twist without e)
  int twist_rate = -1;         // r = omega1/N - omega2
  int motor_current = -1;      // DC motor with L > 0
  int speed_integral = -1;     // servo velocity-loop integrator
  int bristle = -1;            // LuGre s
  int memory = -1;             // fading-memory z (form 6)
  int bouc_wen = -1;           // Bouc-Wen w (form 7)
  int brake_capacity = -1;     // powder-brake torque capacity after the lag
  int brake_temperature = -1;  // powder-brake lumped temperature
  int dissipated_energy = -1;  // integral of the loss power
  std::size_t size = 0;

  // Discrete (form 5): the last switch point and the branch, changed only at located events.
  int anchor_twist = -1;
  int anchor_torque = -1;
  int anchor_loading = -1;   // 1 loading, 0 unloading
  int twist_direction = -1;  // sign of Delta' since the last reversal
  std::size_t discrete_size = 0;

  // Witnesses.
  int witness_upper_flank = -1;  // Delta - b/2
  int witness_lower_flank = -1;  // Delta + b/2
  int witness_reversal = -1;     // Delta'
  int witness_zero_torque = -1;  // form-5 spring torque
  std::size_t witness_count = 0;
};

}  // namespace wavebench::model
