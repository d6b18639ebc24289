#pragma once
// Parameters of the strain-wave gear model (model.md, the gear specification). SI units throughout:
// rad, s, N*m, kg*m^2, N*m/rad, A, V, Ohm. Parameters hold no changing data; the model reads
// them, the integrators never touch them.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "wavebench/model/powder_brake_params.hpp"

namespace wavebench::model {

// --- Kinematics (model.md §1) -------------------------------------------------------------
struct GearGeometry {
  int z_flex = 0;          // z_F, teeth on the Flexspline
  int z_circ = 0;          // z_C, teeth on the Circular Spline
  int wave_number = 2;     // U, lobes of the wave generator
  double ratio = 0.0;      // N = z_F / (z_C - z_F) with CS fixed, Flexspline output
  int direction_sign = 1;  // s: bench output direction relative to the model's theta2
};

// --- Transmission error excitation (model.md §3) ------------------------------------------
// e = sum_j A_j sin(a_j*theta1 + b_j*theta2 + phi_j); frequency at constant speed
// (a_j + b_j/N) * f_H. Every term keeps the name of its physical source for attribution.
enum class TeFamily {
  kWaveGenerator,     // (1, 0)
  kHousing,           // (U, 0)
  kTangentialOutput,  // (U, U) dF_i1, dF_i3
  kTangentialFixed,   // (U, 0) dF_i2
  kOutputAssembly,    // (U, U) T1k
  kToothMesh,         // (U*z_C, 0) base pitch
  kOutputOnceRev,     // (0, 1)
  kCustom,
};

struct TeTerm {
  std::string source;  // e.g. "dF_i1 (Flexspline tangential composite error)"
  TeFamily family = TeFamily::kCustom;
  double amplitude_rad = 0;  // at the output
  double order_input = 0;    // a: cycles per wave-generator revolution
  double order_output = 0;   // b: cycles per output revolution
  double phase_rad = 0;
};

// Seed 001's error-source form, converted into TeTerms by te_terms_from_error_sources().
struct ErrorSource {
  std::string name;  // "dF_i1", "dF_i2", "dF_i3", "dS_fix", "df_i1", "df_i2", "T1k_3", "T1l_7"
  double tolerance_m = 0;  // the source's error in metres (configs give um)
  double phase_rad = 0;
};
struct ErrorSourceSet {
  std::vector<ErrorSource> sources;
  double pitch_diameter_m = 0;        // d_w
  double pressure_angle_rad = 0;      // alpha_n
  double tooth_pairs_in_contact = 1;  // N_c (mean)
};

// --- Stiffness (model.md §4), acting on the backlash-filtered twist x = g(Delta) ----------
struct StiffnessHarmonic {  // angle-periodic variation
  double amplitude = 0;     // N*m/rad for form 1; relative (dimensionless) as a factor on 2-4
  double order_input = 0;
  double order_output = 0;
  double phase_rad = 0;
};
struct LinearPeriodicStiffness {  // 1: k = k0 + sum k_p cos(...), T = k x
  double k0 = 0;
  std::vector<StiffnessHarmonic> harmonics;
};
struct CubicStiffness {  // 2: T = k1 x + k3 x^3
  double k1 = 0;
  double k3 = 0;
};
struct ThreeSegmentStiffness {  // 3: catalogue K1 to T1, K2 to T2, K3 above; odd
  double k1 = 0, t1 = 0, k2 = 0, t2 = 0, k3 = 0;
};
struct TableStiffness {  // 4: monotone (PCHIP) interpolation of a measured curve, odd-extended
  std::vector<double> twist_rad;  // ascending, starting at 0
  std::vector<double> torque_nm;
};
struct HystereticBranchStiffness {  // 5: seed 001, x in arcsec; K(x) = A x^2 + B x + C [N*m/arcsec]
  double a_load = 0, b_load = 0, c_load = 0;        // K2 while |torque| rises
  double a_unload = 0, b_unload = 0, c_unload = 0;  // K1 while |torque| falls
};
struct FadingMemoryStiffness {  // 6: T = a x^3 + b x^2 + c x + z, z' = A x' - B z
  double a = 0, b = 0, c = 0;
  double memory_gain = 0;   // A
  double memory_decay = 0;  // B [1/s]
};
struct BoucWenStiffness {  // 7: T = alpha k x + (1 - alpha) k w
  double k = 0, alpha = 0.5, beta = 0, gamma = 0, n = 1;
};
using StiffnessLaw =
    std::variant<LinearPeriodicStiffness, CubicStiffness, ThreeSegmentStiffness, TableStiffness,
                 HystereticBranchStiffness, FadingMemoryStiffness, BoucWenStiffness>;

struct StiffnessParams {
  StiffnessLaw law;
  std::vector<StiffnessHarmonic> modulation;  // relative factor (1 + sum ...) on forms 2-4
  std::optional<double> mean_stiffness;       // K-bar for damping ratio; derived if absent
};

// --- Backlash (model.md §5) ---------------------------------------------------------------
struct BacklashParams {
  double total_rad = 0;      // b: dead zone is |Delta| <= b/2
  double smoothing_rad = 0;  // epsilon: 0 = sharp dead zone with event location
};

// --- Damping ----------------------------------------------------------------------------
struct MeshDamping {
  std::optional<double> coefficient;    // c [N*m*s/rad]
  std::optional<double> damping_ratio;  // zeta: c = 2 zeta sqrt(J_eq K-bar)
};

// --- Friction (model.md §6): at the wave generator, or at the output bearing ---------------
struct NoFriction {};
struct CoulombStribeckFriction {
  double coulomb = 0, static_torque = 0, stribeck_speed = 1, viscous = 0;
  double smoothing_speed = 1e-4;  // tanh regularisation of sign(omega)
};
struct LuGreFriction {
  double sigma0 = 0, sigma1 = 0, sigma2 = 0;
  double coulomb = 0, static_torque = 0, stribeck_speed = 1;
};
using FrictionLaw = std::variant<NoFriction, CoulombStribeckFriction, LuGreFriction>;
// Which shaft the friction law's speed is and which inertia its torque acts on.
enum class FrictionSide { kInput, kOutput };

// --- Input drive (model.md §2) ------------------------------------------------------------
struct Sinusoid {  // offset + amplitude sin(2 pi f t + phase)
  double offset = 0, amplitude = 0, frequency_hz = 0, phase_rad = 0;
};
struct TorqueInput {
  Sinusoid torque;
};
struct DcMotorInput {  // T_m = K_m i - T_0; u = R i + L i' + K_e omega1 (L = 0: algebraic)
  double resistance = 0, inductance = 0, torque_constant = 0, back_emf_constant = 0;
  double no_load_torque = 0;
  Sinusoid voltage;
};
struct ServoDriveInput {              // cascaded position -> velocity (PI) -> torque, with limits
  double position_gain = 0;           // [1/s]
  double velocity_gain = 0;           // [N*m*s/rad]
  double velocity_integral_time = 0;  // [s], 0 = no integral action
  double torque_limit = 0;            // [N*m], 0 = none
  double speed_limit = 0;             // [rad/s], 0 = none
  double speed_setpoint = 0;          // [rad/s] at the input; used when position control is off
  bool position_control = false;
  double position_setpoint = 0;  // [rad] at the input
};
struct KinematicInput {         // prescribed theta1(t): constant speed, ramp, or a measured trace
  double speed = 0;             // [rad/s] at the input, after the ramp
  double ramp_time = 0;         // [s] from standstill to speed, 0 = at speed from t = 0
  std::vector<double> trace_t;  // optional trace (overrides speed): times [s]
  std::vector<double> trace_theta;  // input angles [rad]
};
using InputDrive = std::variant<TorqueInput, DcMotorInput, ServoDriveInput, KinematicInput>;

// --- Load (model.md §7) -------------------------------------------------------------------
struct LoadParams {
  Sinusoid output_torque;              // T_L + T_iL sin(w_L t), opposes nothing: signed
  Sinusoid drive_ripple;               // T_d + T_id sin(w_d t) on the input side
  double output_drag_coulomb = 0;      // bearing/seal drag opposing omega2 [N*m]
  double drag_smoothing_speed = 1e-3;  // [rad/s]
  std::optional<PowderBrakeParams> brake;
  double brake_current_a = 0;  // constant coil current of the brake
};

// --- Defects of a simulated unit (issue #11: proving the twin's diagnosis) ----------------
// A local tooth error: a short pulse in e each time the damaged tooth meshes. A Flexspline
// tooth turns with the output, so a lobe of the wave generator meets it each 2*pi/U of the
// relative angle theta1 + theta2 (lines at (kU, kU): output orders k*U*(N + 1)); a Circular
// Spline tooth is fixed, so a lobe meets it each 2*pi/U of theta1 (lines at (kU, 0): output
// orders k*U*N). gear_defects.hpp evaluates both.
enum class DefectPart { kFlexspline, kCircularSpline };
struct ToothDefect {
  DefectPart part = DefectPart::kFlexspline;
  int tooth = 0;             // which tooth (0 .. z - 1 of its part): where the pulse sits
  double amplitude_rad = 0;  // peak of the pulse in e (as a TE term: TE = -e for a rigid gear)
  double width = 0.5;        // full width as a fraction of the interval between two meshes
  double onset_rev = 0;      // output revolutions turned before the defect appears
};
// A once-per-output-revolution term whose amplitude grows with the output revolutions turned
// after onset (wear of the output bearing follows the distance rolled, not the clock).
struct RisingOnceRevDefect {
  double growth_rad_per_rev = 0;
  double phase_rad = 0;
  double onset_rev = 0;
};
struct GearDefects {
  std::vector<ToothDefect> teeth;
  std::vector<RisingOnceRevDefect> rising_once_per_rev;
  bool empty() const noexcept { return teeth.empty() && rising_once_per_rev.empty(); }
};

// --- The whole gear system ---------------------------------------------------------------
struct GearParams {
  std::string name;
  GearGeometry geometry;
  double inertia_input = 0;      // J1: motor rotor + wave generator [kg*m^2]
  double inertia_output = 0;     // J2: Flexspline + flange + load [kg*m^2]
  double viscous_input = 0;      // C_j [N*m*s/rad]
  double viscous_output = 0;     // C_z [N*m*s/rad]
  std::vector<TeTerm> te_terms;  // Fourier form plus converted error sources
  StiffnessParams stiffness;
  BacklashParams backlash;
  MeshDamping damping;
  FrictionLaw friction = NoFriction{};
  FrictionSide friction_side = FrictionSide::kInput;
  InputDrive input = KinematicInput{};
  LoadParams load;
  double nominal_input_speed = 0;  // [rad/s] reference motion for deviation coordinates
  // Only the simulated bench's plant takes defects; GearModel refuses a gear that has any.
  GearDefects defects;
};

}  // namespace wavebench::model
