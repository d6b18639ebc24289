#include "parsed_request.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "quoted_value.hpp"
#include "wavebench/procedures/run_limits.hpp"

namespace wavebench::procedures {

namespace {

// Keys of a request's options that belong to the run, not to the procedure.
constexpr const char* kLimitsKey = "limits";
constexpr const char* kCalibrateKey = "calibrate_twin";
constexpr const char* kLostMotionFractionKey = "lost_motion_fraction";

// The spec's lost motion is measured at its fraction of rated torque: the run measures there.
void apply_lost_motion_fraction(const ProductSpec& spec, const std::string& procedure,
                                nlohmann::json& options) {
  const double fraction = *spec.lost_motion_fraction;
  const auto it = options.find(kLostMotionFractionKey);
  if (it == options.end()) {
    options[kLostMotionFractionKey] = fraction;
  } else if (!it->is_number() || std::abs(it->get<double>() - fraction) > 1e-12) {
    throw std::invalid_argument(procedure + "." + kLostMotionFractionKey + ": got '" +
                                quoted_value(*it) + "', expected " +
                                nlohmann::json(fraction).dump() + " (spec " + spec.name +
                                " measures lost motion at that fraction of rated torque)");
  }
}

}  // namespace

ParsedRequest parse_request(const RunRequest& request) {
  if (!request.options.is_object()) {
    throw std::invalid_argument("options: got '" + quoted_value(request.options.dump()) +
                                "', expected an object of option keys");
  }
  nlohmann::json options = request.options;
  nlohmann::json limits = request.spec ? request.spec->run_limits() : nlohmann::json::object();
  if (options.contains(kLimitsKey)) {
    validate_limits(options[kLimitsKey]);
    // The request's own limits on top of the spec's (a tighter check for one run).
    for (const auto& [key, value] : options[kLimitsKey].items()) limits[key] = value;
    options.erase(kLimitsKey);
  }
  bool calibrate = true;
  if (options.contains(kCalibrateKey)) {
    if (!options[kCalibrateKey].is_boolean()) {
      throw std::invalid_argument(std::string(kCalibrateKey) + ": got '" +
                                  quoted_value(options[kCalibrateKey].dump()) +
                                  "', expected true or false");
    }
    calibrate = options[kCalibrateKey].get<bool>();
    options.erase(kCalibrateKey);
  }
  const ProcedureEntry* entry = find_procedure(request.procedure);
  if (entry == nullptr) {
    throw std::invalid_argument("procedure: got '" + quoted_value(request.procedure) +
                                "', expected " + procedure_name_list());
  }
  // Both lost-motion methods (bench.md §4) read lost motion at the spec's fraction.
  if (request.spec && request.spec->lost_motion_fraction &&
      (request.procedure == "lost-motion" || request.procedure == "torsional")) {
    apply_lost_motion_fraction(*request.spec, request.procedure, options);
  }
  auto parsed = parse_procedure(*entry, options);
  return {std::move(parsed.procedure), std::move(parsed.options), limits, calibrate,
          parsed.repeats};
}

}  // namespace wavebench::procedures
