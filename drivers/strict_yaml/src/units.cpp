#include "wavebench/strict_yaml/units.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "wavebench/model/angle_units.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"

namespace wavebench::strict_yaml {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRev = 2.0 * kPi;

struct Unit {
  const char* name;
  double factor;  // SI = factor * value + offset
  double offset = 0.0;
};

// The magnitude no config value of a dimension exceeds (SI, and as the refusal writes it):
// beyond it a value is a typo or an attack, and products of such values overflow (a stiffness
// of 1e308 N*m/rad made the twin's torques infinite). Keys with a meaning bound themselves
// tighter where they are declared.
struct Ceiling {
  double si;
  const char* as_written;
};

struct DimensionInfo {
  Dimension dimension;
  const char* label;
  std::vector<Unit> units;
  Ceiling ceiling;
};

const std::vector<DimensionInfo>& table() {
  static const std::vector<DimensionInfo> dims = {
      {Dimension::kDimensionless,
       "a dimensionless number",
       {{"", 1}, {"1", 1}, {"%", 0.01}},
       {1e12, "1e12"}},  // any ratio, scale or count of sense
      {Dimension::kAngle,
       "an angle",
       {{"rad", 1},
        {"mrad", 1e-3},
        {"urad", 1e-6},
        {"deg", model::kRadPerDeg},
        {"arcmin", model::kRadPerArcmin},
        {"arcsec", model::kRadPerArcsec},
        {"rev", kRev}},
       {1e9, "1e9 rad"}},  // about 1.6e8 turns: more than any trace or run turns
      {Dimension::kAngularSpeed,
       "an angular speed",
       {{"rad/s", 1},
        {"deg/s", model::kRadPerDeg},
        {"rpm", kRev / 60.0},
        {"rev/min", kRev / 60.0},
        {"rev/s", kRev},
        {"Hz", kRev}},
       {1e5, "1e5 rad/s"}},  // about 955 000 rpm: no gear input turns faster
      {Dimension::kLength,
       "a length",
       {{"m", 1}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}},
       {1e3, "1 km"}},  // no bench part is larger
      {Dimension::kTorque,
       "a torque",
       {{"N*m", 1}, {"Nm", 1}, {"mN*m", 1e-3}, {"mNm", 1e-3}, {"kN*m", 1e3}, {"kNm", 1e3}},
       {1e7, "1e7 N*m"}},  // ten times the rating of the largest strain-wave gears
      {Dimension::kStiffness,
       "a torsional stiffness",
       {{"N*m/rad", 1},
        {"Nm/rad", 1},
        {"kN*m/rad", 1e3},
        {"N*m/deg", 1 / model::kRadPerDeg},
        {"N*m/arcmin", 1 / model::kRadPerArcmin},
        {"Nm/arcmin", 1 / model::kRadPerArcmin},
        {"N*m/arcsec", 1 / model::kRadPerArcsec},
        {"Nm/arcsec", 1 / model::kRadPerArcsec}},
       {1e10, "1e10 N*m/rad"}},  // far stiffer than any gear; stiffer overflows the twin
      {Dimension::kQuadraticStiffness,
       "a quadratic stiffness coefficient",
       {{"N*m/rad^2", 1}, {"N*m/arcsec^2", 1 / (model::kRadPerArcsec * model::kRadPerArcsec)}},
       {1e16, "1e16 N*m/rad^2"}},  // k2 at a 1e-3 rad twist below 1e10 N*m/rad
      {Dimension::kCubicStiffness,
       "a cubic stiffness coefficient",
       {{"N*m/rad^3", 1},
        {"N*m/arcsec^3", 1 / (model::kRadPerArcsec * model::kRadPerArcsec * model::kRadPerArcsec)}},
       {1e22, "1e22 N*m/rad^3"}},  // k3 at a 1e-3 rad twist below 1e10 N*m/rad
      {Dimension::kInertia,
       "a moment of inertia",
       {{"kg*m^2", 1}, {"kg*cm^2", 1e-4}, {"g*cm^2", 1e-7}, {"kg*mm^2", 1e-6}},
       {1e6, "1e6 kg*m^2"}},  // a flywheel of tonnes
      {Dimension::kDamping,
       "a rotational damping coefficient",
       {{"N*m*s/rad", 1}, {"Nms/rad", 1}, {"N*m*s", 1}, {"mN*m*s/rad", 1e-3}},
       {1e9, "1e9 N*m*s/rad"}},  // beyond any bearing or brake
      {Dimension::kTime,
       "a time",
       {{"s", 1}, {"ms", 1e-3}, {"us", 1e-6}, {"min", 60}},
       {1e7, "1e7 s"}},  // about 4 months: longer than any run, timeout or lag
      {Dimension::kFrequency,
       "a frequency",
       {{"Hz", 1}, {"kHz", 1e3}, {"MHz", 1e6}},
       {1e9, "1 GHz"}},  // beyond any sample rate or excitation here
      {Dimension::kRate,
       "a rate",
       {{"1/s", 1}, {"/s", 1}},
       {1e9, "1e9 1/s"}},  // beyond any loop gain or decay rate
      {Dimension::kCurrent,
       "a current",
       {{"A", 1}, {"mA", 1e-3}},
       {1e4, "10 kA"}},  // beyond any coil or motor of a bench
      {Dimension::kVoltage,
       "a voltage",
       {{"V", 1}, {"mV", 1e-3}, {"kV", 1e3}},
       {1e5, "100 kV"}},  // beyond any supply of a bench
      {Dimension::kResistance,
       "a resistance",
       {{"Ohm", 1}, {"ohm", 1}, {"mOhm", 1e-3}, {"kOhm", 1e3}},
       {1e9, "1 GOhm"}},  // an open circuit
      {Dimension::kInductance,
       "an inductance",
       {{"H", 1}, {"mH", 1e-3}, {"uH", 1e-6}},
       {1e3, "1 kH"}},  // beyond any winding
      {Dimension::kTorqueConstant,
       "a torque constant",
       {{"N*m/A", 1}, {"Nm/A", 1}},
       {1e4, "1e4 N*m/A"}},  // beyond any motor
      {Dimension::kBackEmfConstant,
       "a back-EMF constant",
       {{"V*s/rad", 1}, {"V/(rad/s)", 1}, {"V/krpm", 60.0 / (kRev * 1000.0)}},
       {1e4, "1e4 V*s/rad"}},  // beyond any motor
      {Dimension::kTemperature,
       "a temperature",
       {{"degC", 1}, {"K", 1, -273.15}},
       {1e4, "1e4 degC"}},  // everything melts before
      {Dimension::kHeatCapacity,
       "a heat capacity",
       {{"J/K", 1}},
       {1e9, "1e9 J/K"}},  // tonnes of metal
      {Dimension::kThermalResistance,
       "a thermal resistance",
       {{"K/W", 1}},
       {1e6, "1e6 K/W"}},  // perfect insulation
  };
  return dims;
}

const DimensionInfo& info(Dimension dimension) {
  for (const auto& d : table()) {
    if (d.dimension == dimension) return d;
  }
  return table().front();
}

void replace_all(std::string& s, std::string_view from, std::string_view to) {
  for (std::size_t pos = s.find(from); pos != std::string::npos;
       pos = s.find(from, pos + to.size())) {
    s.replace(pos, from.size(), to);
  }
}

// Spellings people type: "N·m", "kg·m²", "µm", "Ω", "°C", "N m".
std::string normalise_unit(std::string_view raw) {
  std::string u(raw);
  replace_all(u, "\xC2\xB7", "*");      // middle dot
  replace_all(u, "\xE2\x8B\x85", "*");  // dot operator
  replace_all(u, "\xC2\xB5", "u");      // micro sign
  replace_all(u, "\xCE\xBC", "u");      // greek mu
  replace_all(u, "\xC2\xB2", "^2");
  replace_all(u, "\xC2\xB3", "^3");
  replace_all(u, "\xCE\xA9", "Ohm");
  replace_all(u, "\xE2\x84\xA6", "Ohm");
  replace_all(u,
              "\xC2\xB0"
              "C",
              "degC");
  replace_all(u, "\xC2\xB0", "deg");
  replace_all(u, "**", "^");
  std::string out;
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (u[i] == ' ') {
      // "N m" means "N*m"; spaces around operators are dropped.
      const bool between_words = !out.empty() && out.back() != '*' && out.back() != '/' &&
                                 i + 1 < u.size() && u[i + 1] != ' ' && u[i + 1] != '*' &&
                                 u[i + 1] != '/';
      if (between_words) out += '*';
      continue;
    }
    out += u[i];
  }
  return out;
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

std::optional<Unit> find_unit(const DimensionInfo& d, const std::string& name) {
  for (const auto& u : d.units) {
    if (name == u.name) return u;
  }
  return std::nullopt;
}

std::string unit_list(const DimensionInfo& d) {
  std::string s;
  for (const auto& u : d.units) {
    if (std::string_view(u.name).empty()) continue;
    if (!s.empty()) s += ", ";
    s += u.name;
  }
  return s;
}

}  // namespace

std::string describe(Dimension dimension) {
  const auto& d = info(dimension);
  if (dimension == Dimension::kDimensionless) return d.label;
  std::string s = d.label;
  s += " (a number in SI or one of: " + unit_list(d) + ")";
  return s;
}

std::vector<std::string> accepted_units(Dimension dimension) {
  std::vector<std::string> out;
  for (const auto& u : info(dimension).units) out.emplace_back(u.name);
  return out;
}

double checked_si(double value, const std::string& key) {
  if (!std::isfinite(value)) {
    throw RefusedConfig(key, std::to_string(value), "a finite number");
  }
  return value;
}

double parse_quantity(std::string_view text, Dimension dimension, const std::string& key,
                      const std::string& source) {
  const std::string s = trim(text);
  const std::string value_text(text);
  // from_chars does not accept a leading '+'.
  const std::size_t start = (!s.empty() && s[0] == '+') ? 1 : 0;
  double number = 0;
  const auto [ptr, ec] = std::from_chars(s.data() + start, s.data() + s.size(), number);
  if (ec != std::errc() || ptr == s.data() + start) {
    throw RefusedConfig(key, value_text,
                        "a number followed by an optional unit: " + describe(dimension), source);
  }
  if (!std::isfinite(number)) throw RefusedConfig(key, value_text, "a finite number", source);
  const std::string unit = normalise_unit(trim(std::string_view(ptr, s.data() + s.size() - ptr)));
  const auto& expected = info(dimension);
  const auto within_ceiling = [&](double si) {
    if (!std::isfinite(si)) throw RefusedConfig(key, value_text, "a finite number", source);
    if (std::abs(si) > expected.ceiling.si) {
      throw RefusedConfig(
          key, value_text,
          std::string(expected.label) + " of magnitude at most " + expected.ceiling.as_written,
          source);
    }
    return si;
  };
  if (unit.empty()) return within_ceiling(number);  // a bare number is SI, quoted or not
  if (const auto u = find_unit(expected, unit))
    return within_ceiling(u->factor * number + u->offset);
  // Say what the unit is, if it is one at all: "N*m is a torque" is the useful hint.
  for (const auto& other : table()) {
    if (other.dimension == dimension) continue;
    if (find_unit(other, unit)) {
      throw RefusedConfig(key, value_text,
                          describe(dimension) + ", but '" + unit + "' is " + other.label, source);
    }
  }
  throw RefusedConfig(key, value_text, describe(dimension) + "; unknown unit '" + unit + "'",
                      source);
}

}  // namespace wavebench::strict_yaml
