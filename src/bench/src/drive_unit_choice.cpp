#include "wavebench/bench/drive_unit_choice.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace wavebench::bench {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

// Units per input revolution (per rev/s, per rev/s²); counts have none of their own.
struct NamedUnit {
  const char* name;
  double per_rev;
  bool advertised = true;  // spelling variants are accepted, not listed in messages
};

const std::vector<NamedUnit>& units_of(DriveQuantity q) {
  static const std::vector<NamedUnit> position{
      {"counts", 0}, {"rev", 1}, {"deg", 360}, {"rad", kTwoPi}};
  static const std::vector<NamedUnit> velocity{
      {"counts/s", 0}, {"rpm", 60}, {"rev/s", 1}, {"deg/s", 360}, {"rad/s", kTwoPi}};
  static const std::vector<NamedUnit> acceleration{{"counts/s²", 0},
                                                   {"counts/s^2", 0, false},
                                                   {"counts/s2", 0, false},
                                                   {"rpm/s", 60},
                                                   {"rev/s²", 1},
                                                   {"rev/s^2", 1, false},
                                                   {"rev/s2", 1, false},
                                                   {"deg/s²", 360},
                                                   {"deg/s^2", 360, false},
                                                   {"deg/s2", 360, false},
                                                   {"rad/s²", kTwoPi},
                                                   {"rad/s^2", kTwoPi, false},
                                                   {"rad/s2", kTwoPi, false}};
  switch (q) {
    case DriveQuantity::kPosition:
      return position;
    case DriveQuantity::kVelocity:
      return velocity;
    case DriveQuantity::kAcceleration:
      break;
  }
  return acceleration;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

}  // namespace

std::string expected_drive_units(DriveQuantity q) {
  std::string list;
  for (const auto& u : units_of(q)) {
    if (!u.advertised) continue;
    list += (list.empty() ? "" : ", ") + std::string(u.name);
  }
  const char* example = q == DriveQuantity::kPosition   ? "\"0.001 deg\""
                        : q == DriveQuantity::kVelocity ? "\"0.1 rpm\""
                                                        : "\"0.1 rpm/s\"";
  return list + " (a fixed unit may carry a factor > 0, e.g. " + example + ") or factor_group";
}

DriveUnitChoice parse_drive_unit(const std::string& text, DriveQuantity q) {
  const std::string t = trim(text);
  DriveUnitChoice c;
  c.text = t;
  if (t == "factor_group") {
    c.kind = DriveUnitChoice::Kind::kFactorGroup;
    return c;
  }
  // "[factor] unit": the factor is how many of the named unit one drive unit is.
  double factor = 1;
  std::string name = t;
  if (!t.empty() && (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '.')) {
    char* end = nullptr;
    factor = std::strtod(t.c_str(), &end);
    name = trim(std::string(end));
    if (name.empty() || !(factor > 0) || !std::isfinite(factor))
      throw std::invalid_argument(expected_drive_units(q));
  }
  for (const auto& u : units_of(q)) {
    if (name != u.name) continue;
    if (u.per_rev == 0) {
      if (factor != 1) throw std::invalid_argument(expected_drive_units(q));
      c.kind = DriveUnitChoice::Kind::kCounts;
      return c;
    }
    c.kind = DriveUnitChoice::Kind::kFixed;
    c.per_rev = u.per_rev / factor;
    return c;
  }
  throw std::invalid_argument(expected_drive_units(q));
}

}  // namespace wavebench::bench
