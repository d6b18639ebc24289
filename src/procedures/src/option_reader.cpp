#include "wavebench/procedures/option_reader.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "quoted_value.hpp"

namespace wavebench::procedures {

namespace {

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string number_range(double min, double max, bool min_inclusive) {
  return std::string(min_inclusive ? "a number >= " : "a number > ") + format(min) +
         (std::isfinite(max) ? " and <= " + format(max) : "");
}

}  // namespace

nlohmann::json OptionSpec::to_json() const {
  nlohmann::json j = {{"name", name}, {"type", type}, {"unit", unit}, {"default", default_value}};
  if (minimum) j["minimum"] = *minimum;
  if (maximum && std::isfinite(*maximum)) j["maximum"] = *maximum;
  if (minimum) j["exclusive_minimum"] = exclusive_minimum;
  if (min_items) j["min_items"] = *min_items;
  if (max_items) j["max_items"] = *max_items;
  j["description"] = description;
  return j;
}

OptionReader::OptionReader(const nlohmann::json& options, std::string scope,
                           const std::vector<OptionSpec>& schema)
    : options_(&options), scope_(std::move(scope)) {
  if (!options.is_object()) {
    throw std::invalid_argument(scope_ + " options: got '" + quoted_value(options) +
                                "', expected an object of option keys");
  }
  for (const auto& [key, value] : options.items()) {
    bool known = false;
    std::string list;
    for (const auto& spec : schema) {
      known = known || key == spec.name;
      list += list.empty() ? spec.name : ", " + spec.name;
    }
    if (!known) {
      throw std::invalid_argument(scope_ + ": unknown option '" + quoted_value(key) + "' (value '" +
                                  quoted_value(value) + "'), expected one of: " + list);
    }
  }
}

OptionReader::OptionReader(std::string scope) : scope_(std::move(scope)) {}

bool OptionReader::wanted(OptionSpec spec) {
  if (options_ == nullptr) {
    described_.push_back(std::move(spec));
    return false;
  }
  return options_->contains(spec.name);
}

void OptionReader::fail(const std::string& key, const nlohmann::json& value,
                        const std::string& expected) const {
  throw std::invalid_argument(scope_ + "." + key + ": got '" + quoted_value(value) +
                              "', expected " + expected);
}

void OptionReader::number(const char* key, double& value, double min, double max,
                          bool min_inclusive, const OptionDoc& doc) {
  if (!wanted({key, "number", doc.unit, value, min, max, !min_inclusive, {}, {}, doc.description}))
    return;
  const auto& v = options_->at(key);
  const std::string range = number_range(min, max, min_inclusive);
  if (!v.is_number()) fail(key, v, range);
  const double x = v.get<double>();
  if (!std::isfinite(x) || (min_inclusive ? x < min : x <= min) || x > max) fail(key, v, range);
  value = x;
}

void OptionReader::integer(const char* key, int& value, int min, int max, const OptionDoc& doc) {
  if (!wanted({key, "integer", doc.unit, value, min, max, false, {}, {}, doc.description})) return;
  const auto& v = options_->at(key);
  const std::string range = "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  if (!v.is_number_integer()) fail(key, v, range);
  const auto x = v.get<long long>();
  if (x < min || x > max) fail(key, v, range);
  value = static_cast<int>(x);
}

void OptionReader::boolean(const char* key, bool& value, const OptionDoc& doc) {
  if (!wanted({key, "boolean", doc.unit, value, {}, {}, false, {}, {}, doc.description})) return;
  const auto& v = options_->at(key);
  if (!v.is_boolean()) fail(key, v, "true or false");
  value = v.get<bool>();
}

void OptionReader::numbers(const char* key, std::vector<double>& values, double min, double max,
                           bool min_inclusive, std::size_t min_count, const OptionDoc& doc,
                           std::size_t max_count) {
  if (!wanted({key, "number_list", doc.unit, values, min, max, !min_inclusive, min_count, max_count,
               doc.description}))
    return;
  const auto& v = options_->at(key);
  const std::string count =
      "a list of " + std::to_string(min_count) + " to " + std::to_string(max_count) + " numbers";
  if (!v.is_array()) fail(key, v, count);
  if (v.size() < min_count || v.size() > max_count) {
    fail(key, "a list of " + std::to_string(v.size()) + " entries", count);
  }
  const std::string range = number_range(min, max, min_inclusive);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& item = v[i];
    const std::string item_key = std::string(key) + "[" + std::to_string(i) + "]";
    if (!item.is_number()) fail(item_key, item, range);
    const double x = item.get<double>();
    if (!std::isfinite(x) || (min_inclusive ? x < min : x <= min) || x > max) {
      fail(item_key, item, range);
    }
    out.push_back(x);
  }
  values = std::move(out);
}

}  // namespace wavebench::procedures
