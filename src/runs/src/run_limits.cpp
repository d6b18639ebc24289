#include "wavebench/runs/run_limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "quoted_value.hpp"

namespace wavebench::runs {

namespace {

constexpr const char* kLimits[] = {
    "static_p2p_arcmin",         "static_std_arcmin",  "static_abs_mean_arcmin",
    "static_lost_motion_arcmin", "lost_motion_arcmin", "min_stiffness_nm_per_rad",
    "dynamic_p2p_arcsec",        "dynamic_rms_arcsec", "twin_residual_rms_arcsec"};

class Checker {
 public:
  Checker(const nlohmann::json& limits, LimitVerdict& verdict) : limits_(limits), v_(verdict) {}
  // measured <= limit (or >= for a minimum)
  void check(const char* key, double measured, const std::string& what, bool minimum = false) {
    if (!limits_.contains(key) || !std::isfinite(measured)) return;
    const double limit = limits_.at(key).get<double>();
    const bool ok = minimum ? measured >= limit : measured <= limit;
    v_.checks.push_back(
        {{"limit", key}, {"value", limit}, {"measured", measured}, {"what", what}, {"pass", ok}});
    v_.pass = v_.pass.value_or(true) && ok;
  }

 private:
  const nlohmann::json& limits_;
  LimitVerdict& v_;
};

double num(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>()
                                          : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

void validate_limits(const nlohmann::json& limits) {
  if (!limits.is_object()) {
    throw std::invalid_argument("limits: got '" + quoted_value(limits) +
                                "', expected an object of limit names and values");
  }
  for (const auto& [key, value] : limits.items()) {
    bool known = false;
    std::string list;
    for (const char* k : kLimits) {
      known = known || key == k;
      list += list.empty() ? k : std::string(", ") + k;
    }
    if (!known) {
      throw std::invalid_argument("limits." + quoted_value(key) + ": unknown limit (value '" +
                                  quoted_value(value) + "'), expected one of: " + list);
    }
    if (!value.is_number() || !(value.get<double>() > 0)) {
      throw std::invalid_argument("limits." + key + ": got '" + quoted_value(value) +
                                  "', expected a number > 0");
    }
  }
}

LimitVerdict check_limits(const nlohmann::json& limits, const nlohmann::json& results) {
  LimitVerdict v;
  Checker c(limits, v);
  if (const auto it = results.find("static"); it != results.end() && it->is_array()) {
    for (const auto& p : *it) {
      const std::string what = p.value("direction", std::string()) + " " +
                               std::to_string(p.value("load_nm", 0.0)) + " N·m";
      c.check("static_p2p_arcmin", num(p, "p2p_arcmin"), what);
      c.check("static_std_arcmin", num(p, "std_arcmin"), what);
      c.check("static_abs_mean_arcmin", std::abs(num(p, "mean_arcmin")), what);
    }
  }
  if (const auto it = results.find("lost_motion"); it != results.end() && it->is_array()) {
    for (const auto& lm : *it) {
      // A width, positive; results written before it was (forward − reverse, negative under a
      // brake) are judged by their size all the same.
      double largest = std::numeric_limits<double>::quiet_NaN();
      if (const auto per = lm.find("lost_motion_arcmin"); per != lm.end() && per->is_array()) {
        for (const auto& x : *per) {
          if (x.is_number())
            largest = std::isnan(largest) ? std::abs(x.get<double>())
                                          : std::max(largest, std::abs(x.get<double>()));
        }
      }
      c.check("static_lost_motion_arcmin", largest,
              "static " + std::to_string(lm.value("load_nm", 0.0)) + " N·m");
    }
  }
  if (const auto it = results.find("lost_motion_fit"); it != results.end() && it->is_object()) {
    c.check("lost_motion_arcmin", num(*it, "lost_motion_arcmin"), "lost motion");
    if (it->contains("stiffness")) {
      c.check("min_stiffness_nm_per_rad", num((*it)["stiffness"], "k1_nm_per_rad"), "K1", true);
    }
  }
  if (const auto it = results.find("dynamic"); it != results.end() && it->is_object()) {
    c.check("dynamic_p2p_arcsec", num(*it, "p2p_arcsec"), "dynamic TE");
    c.check("dynamic_rms_arcsec", num(*it, "rms_arcsec"), "dynamic TE");
  }
  // Measured − predicted TE of the twin calibrated to this unit: what the gear model cannot
  // explain (a damaged tooth, a loose part). The nominal twin's residual is mostly the encoders'
  // zero offset and the unit's own TE, which the TE limits already judge.
  if (const auto it = results.find("twin"); it != results.end() && it->is_object()) {
    if (const auto cal = it->find("calibration"); cal != it->end() && cal->is_object()) {
      c.check("twin_residual_rms_arcsec", num(*cal, "rms_after_arcsec"),
              "twin residual after calibration");
    }
  }
  return v;
}

}  // namespace wavebench::runs
