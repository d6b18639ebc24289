#include "yaml_section.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>

#include "wavebench/config/config_error.hpp"

namespace wavebench::config {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool yaml_non_finite(const std::string& s) {
  const std::string l = lower(s);
  return l == ".nan" || l == ".inf" || l == "-.inf" || l == "+.inf" || l == "nan" || l == "inf" ||
         l == "-inf" || l == "+inf" || l == "infinity" || l == "-infinity";
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string node_text(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "";
  if (node.IsScalar()) return node.Scalar();
  YAML::Node flow = YAML::Clone(node);
  flow.SetStyle(YAML::EmitterStyle::Flow);
  YAML::Emitter out;
  out << flow;
  return out.c_str();
}

}  // namespace

YamlSection::YamlSection(YAML::Node node, std::string path)
    : node_(std::move(node)), path_(std::move(path)) {
  if (!node_.IsMap()) {
    fail("", node_text(node_), "a mapping of keys to values");
  }
}

YamlSection document_section(const YAML::Node& root) {
  if (!root.IsMap()) {
    throw ConfigError("", node_text(root), "a YAML mapping with the sections of a twin case");
  }
  return YamlSection(root, "");
}

std::string YamlSection::key_path(const std::string& key) const {
  if (path_.empty()) return key;
  if (key.empty()) return path_;
  return path_ + "." + key;
}

void YamlSection::fail(const std::string& key, const std::string& value,
                       const std::string& expected) const {
  // A required key that is missing is most often misspelt: point at the look-alike.
  if (!key.empty() && !node_[key].IsDefined()) {
    for (const auto& kv : node_) {
      const std::string other = kv.first.as<std::string>();
      if (used_.count(other) == 0 && edit_distance(lower(other), lower(key)) <= 2) {
        throw ConfigError(key_path(key), value,
                          expected + " (the section has '" + other + "': a misspelling?)");
      }
    }
  }
  throw ConfigError(key_path(key), value, expected);
}

void YamlSection::require_within(const std::string& key, double value, double lo, double hi,
                                 const std::string& expected) const {
  if (value >= lo && value <= hi) return;
  std::ostringstream range;
  range << expected << " in [" << lo << ", " << hi << "]";
  fail(key, value_text(key), range.str());
}

std::string YamlSection::value_text(const std::string& key) const {
  return node_text(node_[key]);
}

bool YamlSection::has(const std::string& key) const {
  known_.insert(key);
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

YAML::Node YamlSection::get(const std::string& key) {
  used_.insert(key);
  known_.insert(key);
  return node_[key];
}

double YamlSection::quantity(const std::string& key, Dimension dimension) {
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) fail(key, "", describe(dimension) + " (the key is required)");
  if (!n.IsScalar()) fail(key, node_text(n), describe(dimension));
  const std::string& s = n.Scalar();
  if (yaml_non_finite(s)) fail(key, s, "a finite number");
  return parse_quantity(s, dimension, key_path(key));
}

double YamlSection::quantity_or(const std::string& key, Dimension dimension, double fallback) {
  known_.insert(key);
  return has(key) ? quantity(key, dimension) : fallback;
}

std::optional<double> YamlSection::optional_quantity(const std::string& key, Dimension dimension) {
  known_.insert(key);
  if (!has(key)) return std::nullopt;
  return quantity(key, dimension);
}

double YamlSection::positive_quantity(const std::string& key, Dimension dimension) {
  const double v = quantity(key, dimension);
  if (!(v > 0)) fail(key, value_text(key), "a value > 0: " + describe(dimension));
  return v;
}

double YamlSection::non_negative_quantity_or(const std::string& key, Dimension dimension,
                                             double fallback) {
  known_.insert(key);
  if (!has(key)) return fallback;
  const double v = quantity(key, dimension);
  if (v < 0) fail(key, value_text(key), "a value >= 0: " + describe(dimension));
  return v;
}

std::vector<double> YamlSection::quantity_list(const std::string& key, Dimension dimension) {
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) {
    fail(key, "", "a list of values, each " + describe(dimension) + " (the key is required)");
  }
  if (!n.IsSequence()) fail(key, node_text(n), "a list of values, each " + describe(dimension));
  if (n.size() > kMaxListItems) {
    fail(key, std::to_string(n.size()) + " values",
         "a list of at most " + std::to_string(kMaxListItems) + " values");
  }
  std::vector<double> out;
  out.reserve(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item_key = key_path(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsScalar()) throw ConfigError(item_key, node_text(n[i]), describe(dimension));
    if (yaml_non_finite(n[i].Scalar())) {
      throw ConfigError(item_key, n[i].Scalar(), "a finite number");
    }
    out.push_back(parse_quantity(n[i].Scalar(), dimension, item_key));
  }
  return out;
}

int YamlSection::integer(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) fail(key, "", "an integer (the key is required)");
  const std::string s = n.IsScalar() ? n.Scalar() : node_text(n);
  int v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (!n.IsScalar() || ec != std::errc() || ptr != s.data() + s.size()) {
    fail(key, s, "an integer");
  }
  return v;
}

int YamlSection::integer_or(const std::string& key, int fallback) {
  known_.insert(key);
  return has(key) ? integer(key) : fallback;
}

std::string YamlSection::text(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) fail(key, "", "a text value (the key is required)");
  if (!n.IsScalar()) fail(key, node_text(n), "a text value");
  return n.Scalar();
}

std::string YamlSection::text_or(const std::string& key, const std::string& fallback) {
  known_.insert(key);
  return has(key) ? text(key) : fallback;
}

bool YamlSection::boolean_or(const std::string& key, bool fallback) {
  known_.insert(key);
  if (!has(key)) return fallback;
  const YAML::Node n = get(key);
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v)) {
    fail(key, node_text(n), "true or false");
  }
  return v;
}

std::string YamlSection::choice(const std::string& key,
                                std::initializer_list<const char*> choices) {
  std::string list;
  for (const char* c : choices) list += (list.empty() ? "" : "|") + std::string(c);
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) fail(key, "", "one of " + list + " (the key is required)");
  const std::string v = n.IsScalar() ? n.Scalar() : node_text(n);
  for (const char* c : choices) {
    if (v == c) return v;
  }
  fail(key, v, "one of " + list);
}

std::string YamlSection::choice_or(const std::string& key,
                                   std::initializer_list<const char*> choices,
                                   const std::string& fallback) {
  known_.insert(key);
  return has(key) ? choice(key, choices) : fallback;
}

YamlSection YamlSection::section(const std::string& key) {
  const YAML::Node n = get(key);
  if (!n.IsDefined() || n.IsNull()) fail(key, "", "a section (the key is required)");
  if (!n.IsMap()) fail(key, node_text(n), "a section (a mapping of keys to values)");
  return YamlSection(n, key_path(key));
}

std::optional<YamlSection> YamlSection::optional_section(const std::string& key) {
  known_.insert(key);
  if (!has(key)) return std::nullopt;
  return section(key);
}

std::vector<YamlSection> YamlSection::section_list(const std::string& key) {
  const YAML::Node n = get(key);
  std::vector<YamlSection> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, node_text(n), "a list of sections");
  if (n.size() > kMaxListItems) {
    fail(key, std::to_string(n.size()) + " items",
         "a list of at most " + std::to_string(kMaxListItems) + " sections");
  }
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) fail(item, node_text(n[i]), "a section (a mapping of keys to values)");
    out.emplace_back(n[i], key_path(item));
  }
  return out;
}

model::Sinusoid YamlSection::sinusoid_or(const std::string& key, Dimension dimension) {
  known_.insert(key);
  model::Sinusoid s;
  if (!has(key)) return s;
  if (node_[key].IsScalar()) {
    s.offset = quantity(key, dimension);
    return s;
  }
  YamlSection sub = section(key);
  s.offset = sub.quantity_or("offset", dimension, 0.0);
  s.amplitude = sub.quantity_or("amplitude", dimension, 0.0);
  s.frequency_hz = sub.non_negative_quantity_or("frequency", Dimension::kFrequency, 0.0);
  sub.require_within("frequency", s.frequency_hz, 0, kMaxSinusoidHz, "a frequency [Hz]");
  s.phase_rad = sub.quantity_or("phase", Dimension::kAngle, 0.0);
  sub.finish();
  return s;
}

void YamlSection::finish() const {
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (used_.count(key)) continue;
    std::string expected = "no such key here";
    std::string best;
    std::size_t best_d = 3;  // suggest only near misses
    for (const auto& k : known_) {
      const std::size_t d = edit_distance(lower(key), lower(k));
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    if (!best.empty()) expected += " (did you mean '" + best + "'?)";
    if (!known_.empty() && best.empty()) {
      std::string list;
      for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
      expected += " (this section knows: " + list + ")";
    }
    throw ConfigError(key_path(key), node_text(kv.second), expected);
  }
}

}  // namespace wavebench::config
