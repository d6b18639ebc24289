#include "wavebench/procedures/product_spec.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <stdexcept>

#include "quoted_value.hpp"
#include "verdict_table.hpp"
#include "wavebench/config/shipped_configs.hpp"
#include "wavebench/strict_yaml/strict_yaml.hpp"
#include "wavebench/strict_yaml/yaml_section.hpp"

namespace wavebench::procedures {

namespace {

using strict_yaml::Dimension;

constexpr std::size_t kMaxSpecName = 64;
constexpr std::size_t kListedSpecs = 20;

// A limit without its unit would be read as SI (radians): 1.0 meant as arcmin is 3438 arcmin.
bool has_unit(const std::string& text) {
  return std::any_of(text.begin(), text.end(),
                     [](char c) {
                       return std::isalpha(static_cast<unsigned char>(c)) != 0 && c != 'e' &&
                              c != 'E';
                     }) ||
         text.find('%') != std::string::npos;
}

// A limit converted back from SI to its key's unit, without the round trip's last-bit noise
// (7 arcmin reads 7, not 7.000000000000001).
double to_12_digits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", v);
  return std::strtod(text, nullptr);
}

ProductSpec read_spec(strict_yaml::YamlSection& doc, const std::string& name) {
  ProductSpec spec;
  spec.name = name;
  spec.model = doc.text("model");
  spec.description = doc.text_or("description", "");
  if (const auto u = doc.optional_choice("undecided", {"fail", "pass", "undecided"})) {
    spec.undecided = *u == "pass"        ? UndecidedCounts::kPass
                     : *u == "undecided" ? UndecidedCounts::kUndecided
                                         : UndecidedCounts::kFail;
  }
  auto limits = doc.section("limits");
  for (const auto& k : verdict_figures()) {
    if (!limits.has(k.spec_key)) continue;
    const std::string written = limits.value_text(k.spec_key);
    if (!has_unit(written)) {
      limits.fail(k.spec_key, written,
                  "a value > 0 with its unit: " + strict_yaml::describe(k.dimension));
    }
    const double si = limits.positive_quantity(k.spec_key, k.dimension);
    spec.limits.push_back({k.spec_key, k.limit, to_12_digits(si / k.per_unit), k.unit});
  }
  if (limits.has("lost_motion_at")) {
    const std::string written = limits.value_text("lost_motion_at");
    if (!limits.has("lost_motion")) {
      limits.fail("lost_motion_at", written, "no lost_motion_at without a lost_motion limit");
    }
    if (written.find('%') == std::string::npos) {
      limits.fail("lost_motion_at", written, "a percentage of rated torque in (0, 100 %]");
    }
    spec.lost_motion_fraction =
        limits.optional_quantity_in("lost_motion_at", Dimension::kDimensionless, 1e-6, 1,
                                    "a percentage of rated torque in (0, 100 %]");
  }
  limits.finish();  // an unknown (misspelt) limit is named before "no limit"
  if (spec.limits.empty()) {
    limits.fail("", "no limit", "at least one limit");
  }
  doc.finish();
  return spec;
}

}  // namespace

nlohmann::json ProductSpec::run_limits() const {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& l : limits) j[l.limit] = l.value;
  return j;
}

nlohmann::json ProductSpec::to_json() const {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& l : limits) {
    list.push_back({{"key", l.key}, {"limit", l.limit}, {"value", l.value}, {"unit", l.unit}});
  }
  return {{"name", name},
          {"model", model},
          {"description", description},
          {"lost_motion_at_percent",
           lost_motion_fraction ? nlohmann::json(*lost_motion_fraction * 100) : nlohmann::json()},
          {"undecided", undecided_counts_name(undecided)},
          {"limits", list}};
}

ProductSpec parse_product_spec(const std::string& yaml_text, const std::string& name,
                               const std::string& source) {
  try {
    const YAML::Node root = strict_yaml::parse_strict_yaml(yaml_text, source);
    auto doc = strict_yaml::document_section(root, source, "a product spec: model and limits");
    return read_spec(doc, name);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
}

ProductSpec load_product_spec(const std::filesystem::path& file) {
  std::string text;
  try {
    text = strict_yaml::read_config_file(file);
  } catch (const strict_yaml::RefusedConfig& e) {
    throw std::invalid_argument(e.what());
  }
  return parse_product_spec(text, file.stem().string(), file.string());
}

std::filesystem::path default_specs_dir() {
  return config::shipped_config_dir() / "specs";
}

std::vector<std::string> product_spec_names(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.path().extension() == ".yaml" && e.is_regular_file(ec)) {
      names.push_back(e.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

ProductSpec find_product_spec(const std::filesystem::path& dir, const std::string& name) {
  const bool well_formed =
      !name.empty() && name.size() <= kMaxSpecName && name.front() != '.' &&
      std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '_' || c == '-';
      });
  const auto names = product_spec_names(dir);
  // Listed in the refusal, at most kListedSpecs of them: a message, not a directory listing.
  std::string known;
  for (std::size_t i = 0; i < names.size() && i < kListedSpecs; ++i) {
    known += (known.empty() ? "" : ", ") + names[i];
  }
  if (names.size() > kListedSpecs) {
    known += ", ... (" + std::to_string(names.size()) + " in all; GET /api/specs lists them)";
  }
  if (known.empty()) known = "(none in " + dir.string() + ")";
  if (!well_formed) {
    throw std::invalid_argument("spec: got '" + quoted_value(name) +
                                "', expected a spec name of 1 to 64 characters A-Z a-z 0-9 . _ - "
                                "(not starting with a dot); known specs: " +
                                known);
  }
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw std::invalid_argument("spec: got '" + name +
                                "', expected one of the known specs: " + known);
  }
  return load_product_spec(dir / (name + ".yaml"));
}

}  // namespace wavebench::procedures
