#include "wavebench/strict_yaml/yaml_section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace wavebench::strict_yaml {
namespace {

constexpr const char* kNoValue = " (the key has no value: write one or leave the key out)";

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

bool absent(const YAML::Node& n) {
  return !n.IsDefined();
}

bool without_value(const YAML::Node& n) {
  return n.IsDefined() && n.IsNull();
}

std::string range_text(double lo, double hi) {
  std::ostringstream out;
  out << "[" << lo << ", " << hi << "]";
  return out.str();
}

std::string range_text(long long lo, long long hi) {
  return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

std::string choice_list(std::initializer_list<const char*> choices) {
  std::string list;
  for (const char* c : choices) list += (list.empty() ? "" : "|") + std::string(c);
  return list;
}

// yaml-cpp's own conversions, so every loader accepts the numbers it always did (0x hex
// integers, 1e6 doubles).
std::optional<long long> integer_of(const YAML::Node& n) {
  long long v = 0;
  if (!n.IsScalar() || !YAML::convert<long long>::decode(n, v)) return std::nullopt;
  return v;
}

std::optional<double> number_of(const YAML::Node& n) {
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v)) {
    return std::nullopt;
  }
  return v;
}

}  // namespace

YamlSection::YamlSection(YAML::Node node, std::string path, std::string source)
    : node_(std::move(node)), path_(std::move(path)), source_(std::move(source)) {
  if (!node_.IsMap()) fail("", node_text(node_), "a mapping of keys to values");
}

YamlSection document_section(const YAML::Node& root, const std::string& source,
                             const std::string& expected) {
  if (!root.IsMap()) throw RefusedConfig("", node_text(root), expected, source);
  return YamlSection(root, "", source);
}

std::string YamlSection::key_path(const std::string& key) const {
  if (path_.empty()) return key;
  if (key.empty()) return path_;
  if (key.front() == '[') return path_ + key;
  return path_ + "." + key;
}

void YamlSection::fail(const std::string& key, const std::string& value,
                       const std::string& expected) const {
  // A required key that is missing is most often misspelt: point at the look-alike.
  if (!key.empty() && key.find('[') == std::string::npos && absent(node_[key])) {
    for (const auto& kv : node_) {
      const std::string other = kv.first.as<std::string>();
      if (used_.count(other) == 0 && edit_distance(lower(other), lower(key)) <= 2) {
        throw RefusedConfig(key_path(key), value,
                            expected + " (the section has '" + other + "': a misspelling?)",
                            source_);
      }
    }
  }
  throw RefusedConfig(key_path(key), value, expected, source_);
}

void YamlSection::require_within(const std::string& key, double value, double lo, double hi,
                                 const std::string& expected) const {
  if (value >= lo && value <= hi) return;
  fail(key, value_text(key), expected + " in " + range_text(lo, hi));
}

std::string YamlSection::value_text(const std::string& key) const {
  return node_text(node_[key]);
}

bool YamlSection::has(const std::string& key) const {
  known_.insert(key);
  return node_[key].IsDefined();
}

bool YamlSection::has_section(const std::string& key) const {
  known_.insert(key);
  const YAML::Node n = node_[key];
  return n.IsDefined() && n.IsMap();
}

std::vector<std::string> YamlSection::keys() const {
  std::vector<std::string> out;
  for (const auto& kv : node_) out.push_back(kv.first.as<std::string>());
  return out;
}

YAML::Node YamlSection::get(const std::string& key) {
  used_.insert(key);
  known_.insert(key);
  return node_[key];
}

std::optional<YAML::Node> YamlSection::present(const std::string& key,
                                               const std::string& expected) {
  known_.insert(key);
  const YAML::Node n = node_[key];
  if (absent(n)) return std::nullopt;
  used_.insert(key);
  if (without_value(n)) fail(key, "", expected + kNoValue);
  return n;
}

double YamlSection::quantity(const std::string& key, Dimension dimension) {
  const YAML::Node n = get(key);
  if (absent(n)) fail(key, "", describe(dimension) + " (the key is required)");
  if (without_value(n)) fail(key, "", describe(dimension) + kNoValue);
  if (!n.IsScalar()) fail(key, node_text(n), describe(dimension));
  const std::string& s = n.Scalar();
  if (yaml_non_finite(s)) fail(key, s, "a finite number");
  return parse_quantity(s, dimension, key_path(key), source_);
}

double YamlSection::quantity_or(const std::string& key, Dimension dimension, double fallback) {
  return optional_quantity(key, dimension).value_or(fallback);
}

std::optional<double> YamlSection::optional_quantity(const std::string& key, Dimension dimension) {
  if (!present(key, describe(dimension))) return std::nullopt;
  return quantity(key, dimension);
}

double YamlSection::positive_quantity(const std::string& key, Dimension dimension) {
  const double v = quantity(key, dimension);
  if (!(v > 0)) fail(key, value_text(key), "a value > 0: " + describe(dimension));
  return v;
}

double YamlSection::non_negative_quantity_or(const std::string& key, Dimension dimension,
                                             double fallback) {
  const std::optional<double> v = optional_quantity(key, dimension);
  if (!v) return fallback;
  if (*v < 0) fail(key, value_text(key), "a value >= 0: " + describe(dimension));
  return *v;
}

std::optional<double> YamlSection::optional_quantity_in(const std::string& key, Dimension dimension,
                                                        double lo, double hi,
                                                        const std::string& expected) {
  const std::optional<double> v = optional_quantity(key, dimension);
  if (v && !(*v >= lo && *v <= hi)) fail(key, value_text(key), expected);
  return v;
}

std::vector<double> YamlSection::quantity_list(const std::string& key, Dimension dimension) {
  const YAML::Node n = get(key);
  if (absent(n)) {
    fail(key, "", "a list of values, each " + describe(dimension) + " (the key is required)");
  }
  if (without_value(n)) fail(key, "", "a list of values, each " + describe(dimension) + kNoValue);
  if (!n.IsSequence()) fail(key, node_text(n), "a list of values, each " + describe(dimension));
  if (n.size() > kMaxListItems) {
    fail(key, std::to_string(n.size()) + " values",
         "a list of at most " + std::to_string(kMaxListItems) + " values");
  }
  std::vector<double> out;
  out.reserve(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!n[i].IsScalar()) fail(item, node_text(n[i]), describe(dimension));
    if (yaml_non_finite(n[i].Scalar())) fail(item, n[i].Scalar(), "a finite number");
    out.push_back(parse_quantity(n[i].Scalar(), dimension, key_path(item), source_));
  }
  return out;
}

std::optional<double> YamlSection::optional_number(const std::string& key, double lo, double hi) {
  const std::string expected = "a number in " + range_text(lo, hi);
  const std::optional<YAML::Node> n = present(key, expected);
  if (!n) return std::nullopt;
  const std::optional<double> v = number_of(*n);
  if (!v || *v < lo || *v > hi) fail(key, node_text(*n), expected);
  return v;
}

double YamlSection::number_or(const std::string& key, double lo, double hi, double fallback) {
  return optional_number(key, lo, hi).value_or(fallback);
}

long long YamlSection::integer(const std::string& key, long long lo, long long hi) {
  known_.insert(key);
  if (absent(node_[key])) {
    fail(key, "", "an integer in " + range_text(lo, hi) + " (the key is required)");
  }
  return *optional_integer(key, lo, hi);
}

std::optional<long long> YamlSection::optional_integer(const std::string& key, long long lo,
                                                       long long hi) {
  const std::string expected = "an integer in " + range_text(lo, hi);
  const std::optional<YAML::Node> n = present(key, expected);
  if (!n) return std::nullopt;
  const std::optional<long long> v = integer_of(*n);
  if (!v || *v < lo || *v > hi) fail(key, node_text(*n), expected);
  return v;
}

long long YamlSection::integer_or(const std::string& key, long long lo, long long hi,
                                  long long fallback) {
  return optional_integer(key, lo, hi).value_or(fallback);
}

std::optional<std::vector<long long>> YamlSection::optional_integer_list(const std::string& key,
                                                                         long long lo,
                                                                         long long hi) {
  const std::string each = "an integer in " + range_text(lo, hi);
  const std::optional<YAML::Node> n = present(key, "a list of integers");
  if (!n) return std::nullopt;
  if (!n->IsSequence()) fail(key, node_text(*n), "a list, each " + each);
  if (n->size() > kMaxListItems) {
    fail(key, std::to_string(n->size()) + " values",
         "a list of at most " + std::to_string(kMaxListItems) + " values");
  }
  std::vector<long long> out;
  for (std::size_t i = 0; i < n->size(); ++i) {
    const std::optional<long long> v = integer_of((*n)[i]);
    if (!v || *v < lo || *v > hi) {
      fail(key + "[" + std::to_string(i) + "]", node_text((*n)[i]), each);
    }
    out.push_back(*v);
  }
  return out;
}

std::string YamlSection::text(const std::string& key) {
  known_.insert(key);
  if (absent(node_[key])) fail(key, "", "a text value (the key is required)");
  return *optional_text(key);
}

std::optional<std::string> YamlSection::optional_text(const std::string& key) {
  const std::optional<YAML::Node> n = present(key, "a text value");
  if (!n) return std::nullopt;
  if (!n->IsScalar()) fail(key, node_text(*n), "a text value");
  return n->Scalar();
}

std::string YamlSection::text_or(const std::string& key, const std::string& fallback) {
  return optional_text(key).value_or(fallback);
}

std::optional<std::vector<std::string>> YamlSection::optional_text_list(const std::string& key) {
  const std::optional<YAML::Node> n = present(key, "a list of text values");
  if (!n) return std::nullopt;
  if (!n->IsSequence()) fail(key, node_text(*n), "a list of text values");
  if (n->size() > kMaxListItems) {
    fail(key, std::to_string(n->size()) + " values",
         "a list of at most " + std::to_string(kMaxListItems) + " values");
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n->size(); ++i) {
    const YAML::Node item = (*n)[i];
    if (!item.IsScalar())
      fail(key + "[" + std::to_string(i) + "]", node_text(item), "a text value");
    out.push_back(item.Scalar());
  }
  return out;
}

std::optional<std::string> YamlSection::optional_label(const std::string& key,
                                                       std::size_t max_bytes) {
  const std::optional<std::string> v = optional_text(key);
  if (!v) return v;
  const std::string expected =
      "a name of 1 to " + std::to_string(max_bytes) + " bytes without < > \" or control characters";
  if (v->empty() || v->size() > max_bytes) fail(key, v->substr(0, 40), expected);
  for (const char c : *v) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '<' || c == '>' || c == '"' || u < 0x20 || u == 0x7F) {
      std::string shown;
      for (const char d : v->substr(0, 60)) {
        const auto du = static_cast<unsigned char>(d);
        shown += (du < 0x20 || du == 0x7F) ? '?' : d;  // the message itself stays one clean line
      }
      fail(key, shown, expected);
    }
  }
  return v;
}

std::optional<bool> YamlSection::optional_boolean(const std::string& key) {
  const std::optional<YAML::Node> n = present(key, "true or false");
  if (!n) return std::nullopt;
  bool v = false;
  if (!n->IsScalar() || !YAML::convert<bool>::decode(*n, v)) {
    fail(key, node_text(*n), "true or false");
  }
  return v;
}

bool YamlSection::boolean_or(const std::string& key, bool fallback) {
  return optional_boolean(key).value_or(fallback);
}

std::string YamlSection::choice(const std::string& key,
                                std::initializer_list<const char*> choices) {
  known_.insert(key);
  if (absent(node_[key])) {
    fail(key, "", "one of " + choice_list(choices) + " (the key is required)");
  }
  return *optional_choice(key, choices);
}

std::optional<std::string> YamlSection::optional_choice(
    const std::string& key, std::initializer_list<const char*> choices) {
  const std::string expected = "one of " + choice_list(choices);
  const std::optional<YAML::Node> n = present(key, expected);
  if (!n) return std::nullopt;
  const std::string v = node_text(*n);
  if (n->IsScalar()) {
    for (const char* c : choices) {
      if (v == c) return v;
    }
  }
  fail(key, v, expected);
}

std::string YamlSection::choice_or(const std::string& key,
                                   std::initializer_list<const char*> choices,
                                   const std::string& fallback) {
  return optional_choice(key, choices).value_or(fallback);
}

YamlSection YamlSection::section(const std::string& key) {
  known_.insert(key);
  if (absent(node_[key])) fail(key, "", "a section (the key is required)");
  return *optional_section(key);
}

std::optional<YamlSection> YamlSection::optional_section(const std::string& key) {
  const std::optional<YAML::Node> n = present(key, "a section (a mapping of keys to values)");
  if (!n) return std::nullopt;
  if (!n->IsMap()) fail(key, node_text(*n), "a section (a mapping of keys to values)");
  return YamlSection(*n, key_path(key), source_);
}

std::vector<YamlSection> YamlSection::section_list(const std::string& key) {
  const std::optional<YAML::Node> n = present(key, "a list of sections");
  std::vector<YamlSection> out;
  if (!n) return out;
  if (!n->IsSequence()) fail(key, node_text(*n), "a list of sections");
  if (n->size() > kMaxListItems) {
    fail(key, std::to_string(n->size()) + " items",
         "a list of at most " + std::to_string(kMaxListItems) + " sections");
  }
  for (std::size_t i = 0; i < n->size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!(*n)[i].IsMap()) {
      fail(item, node_text((*n)[i]), "a section (a mapping of keys to values)");
    }
    out.emplace_back((*n)[i], key_path(item), source_);
  }
  return out;
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
    throw RefusedConfig(key_path(key), node_text(kv.second), expected, source_);
  }
}

}  // namespace wavebench::strict_yaml
