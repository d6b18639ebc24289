#pragma once
// Linearised two-inertia model of the gear about its operating point (model.md §2, seed 003):
// mean stiffness K-bar from the stiffness law at the operating twist, natural frequencies,
// mode shapes, damping ratios and transfer functions from the TE to the response channels.

#include <complex>
#include <string>
#include <vector>

#include "wavebench/model/gear_params.hpp"

namespace wavebench::analysis {

struct LinearGearCoefficients {
  double inertia_input = 0;       // J1 [kg m^2]
  double inertia_output = 0;      // J2
  double ratio = 1;               // N
  double stiffness = 0;           // K-bar at the output [N m/rad]
  double mesh_damping = 0;        // c [N m s/rad]
  double damping_input = 0;       // C_j plus the drive's speed feedback (DC motor K_m K_e / R, ...)
  double damping_output = 0;      // C_z
  bool input_prescribed = false;  // kinematic input: theta1 is given, one degree of freedom
};

struct VibrationMode {
  double natural_frequency_hz = 0;  // undamped
  double damping_ratio = 0;
  double shape_input = 0;   // theta1 / N (input angle referred to the output), normalised
  double shape_output = 0;  // theta2
};

struct LinearisedGear {
  LinearGearCoefficients coefficients;
  double operating_twist_rad = 0;    // x at which K-bar was taken
  double operating_torque_nm = 0;    // mean gear torque used to find it
  std::string stiffness_note;        // how K-bar was obtained
  std::vector<VibrationMode> modes;  // elastic modes (rigid-body mode left out), ascending
};

// Channels of SampledResponse that have a transfer function from the TE e.
// alpha2, omega2, te, theta2_dev, twist, twist_rate, gear_torque.
bool has_te_transfer(const std::string& channel);

// Mean stiffness dT/dx of the law at the twist where it carries `torque` (the operating point).
double mean_stiffness(const model::StiffnessParams& stiffness, double torque, double* twist_out,
                      std::string* note);

LinearisedGear linearise_gear(const model::GearParams& params, double mean_gear_torque);

// Modes of the coefficients (undamped frequencies from the generalised eigenproblem, damping
// ratios from the damped state-space eigenvalues).
std::vector<VibrationMode> vibration_modes(const LinearGearCoefficients& coefficients);

// Complex response of `channel` to a unit TE e = exp(i w t) at frequency_hz (steady state).
std::complex<double> te_transfer(const LinearGearCoefficients& coefficients,
                                 const std::string& channel, double frequency_hz);

// Seed 003's G(s) = theta_z(s)/U(s) for a DC-motor drive (no friction, L = 0), derived from
// J_j th_j'' + C_j th_j' = (K_m/R)(u - K_e th_j') - (K/N)(th_j/N - th_z) - (c/N)(th_j'/N - th_z')
// J_z th_z'' + C_z th_z' = K(th_j/N - th_z) + c(th_j'/N - th_z')
// Coefficients in descending powers of s.
struct Polynomial {
  std::vector<double> coefficients;  // descending powers
  std::complex<double> operator()(std::complex<double> s) const;
};
struct TransferFunction {
  Polynomial numerator;
  Polynomial denominator;
  std::complex<double> operator()(std::complex<double> s) const {
    return numerator(s) / denominator(s);
  }
};
struct DcMotorGearConstants {
  double resistance = 0, torque_constant = 0, back_emf_constant = 0;
  double inertia_motor = 0, inertia_load = 0, damping_motor = 0, damping_load = 0;
  double mesh_damping = 0, stiffness = 0, ratio = 1;
};
TransferFunction dc_motor_output_angle_transfer(const DcMotorGearConstants& constants);

}  // namespace wavebench::analysis
