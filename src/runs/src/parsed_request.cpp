#include "parsed_request.hpp"

#include <stdexcept>
#include <string>

#include "quoted_value.hpp"
#include "wavebench/runs/run_limits.hpp"

namespace wavebench::runs {

namespace {

// Keys of a request's options that belong to the run, not to the procedure.
constexpr const char* kLimitsKey = "limits";
constexpr const char* kCalibrateKey = "calibrate_twin";

}  // namespace

ParsedRequest parse_request(const RunRequest& request) {
  if (!request.options.is_object()) {
    throw std::invalid_argument("options: got '" + quoted_value(request.options.dump()) +
                                "', expected an object of option keys");
  }
  nlohmann::json options = request.options;
  nlohmann::json limits = nlohmann::json::object();
  if (options.contains(kLimitsKey)) {
    limits = options[kLimitsKey];
    validate_limits(limits);
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
  if (request.procedure == "static") {
    const auto o = StaticTeOptions::from_json(options);
    return {StaticTeProcedure(o), o.to_json(), limits, calibrate};
  }
  if (request.procedure == "dynamic") {
    const auto o = DynamicTeOptions::from_json(options);
    return {DynamicTeProcedure(o), o.to_json(), limits, calibrate};
  }
  if (request.procedure == "lost-motion") {
    const auto o = LostMotionOptions::from_json(options);
    return {LostMotionProcedure(o), o.to_json(), limits, calibrate};
  }
  throw std::invalid_argument("procedure: got '" + quoted_value(request.procedure) +
                              "', expected static, dynamic or lost-motion");
}

}  // namespace wavebench::runs
