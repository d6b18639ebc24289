#pragma once
// The one typed reader of every config loader: a mapping with its key path ("brake.link") and
// the source it came from. Every read marks its key as used; finish() then refuses whatever
// was not read, which is how typos get caught. Every refusal is a RefusedConfig naming the
// source, the key path, the value as written and what was expected.
//
// A key that is absent takes the default; a key written with no value ("port:") is refused,
// so a forgotten value never silently becomes a default (or a safety limit switched off).

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "wavebench/strict_yaml/strict_yaml.hpp"
#include "wavebench/strict_yaml/units.hpp"

namespace wavebench::strict_yaml {

// Lists longer than this are refused: no shipped config has more than a few dozen items, and
// a list's length multiplies the work of whatever reads it.
inline constexpr std::size_t kMaxListItems = 10000;

// The lower end of a range open at zero ("(0, 10 s]"): the smallest value above zero.
inline constexpr double kAboveZero = std::numeric_limits<double>::denorm_min();

class YamlSection {
 public:
  // Refuses a node that is not a mapping. `path` is "" at the top of a document.
  YamlSection(YAML::Node node, std::string path, std::string source = {});

  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  std::string key_path(const std::string& key) const;
  // Written in the file (with or without a value). Does not mark the key used.
  bool has(const std::string& key) const;
  // Written as a mapping (for keys that take a value or a section).
  bool has_section(const std::string& key) const;
  // The keys as written, in file order (for mappings whose keys are names, e.g. channels).
  std::vector<std::string> keys() const;

  // Quantities: a plain number is SI, text carries a unit of `dimension` (units.hpp).
  double quantity(const std::string& key, Dimension dimension);
  double quantity_or(const std::string& key, Dimension dimension, double fallback);
  std::optional<double> optional_quantity(const std::string& key, Dimension dimension);
  double positive_quantity(const std::string& key, Dimension dimension);  // required, > 0
  double non_negative_quantity_or(const std::string& key, Dimension dimension, double fallback);
  // Within [lo, hi] (SI); `expected` says so in the file's terms, e.g. "a time in [0, 60 s]".
  std::optional<double> optional_quantity_in(const std::string& key, Dimension dimension, double lo,
                                             double hi, const std::string& expected);
  std::vector<double> quantity_list(const std::string& key, Dimension dimension);

  // Plain numbers without a unit, within [lo, hi].
  std::optional<double> optional_number(const std::string& key, double lo, double hi);
  double number_or(const std::string& key, double lo, double hi, double fallback);

  // Integers (decimal, 0x hex or 0o octal) within [lo, hi].
  long long integer(const std::string& key, long long lo, long long hi);
  std::optional<long long> optional_integer(const std::string& key, long long lo, long long hi);
  long long integer_or(const std::string& key, long long lo, long long hi, long long fallback);
  std::optional<std::vector<long long>> optional_integer_list(const std::string& key, long long lo,
                                                              long long hi);

  std::string text(const std::string& key);
  std::optional<std::string> optional_text(const std::string& key);
  std::string text_or(const std::string& key, const std::string& fallback);
  std::optional<std::vector<std::string>> optional_text_list(const std::string& key);
  // A name or serial (bench, unit, calibration, case): 1..max_bytes of text without markup or
  // quoting characters (< > ") or control characters. Labels end up in HTML reports, the
  // console, CSV headers and the runs index, where such characters are an injection, never a
  // name.
  std::optional<std::string> optional_label(const std::string& key, std::size_t max_bytes = 128);

  std::optional<bool> optional_boolean(const std::string& key);
  bool boolean_or(const std::string& key, bool fallback);

  // One of `choices`; the refusal lists them.
  std::string choice(const std::string& key, std::initializer_list<const char*> choices);
  std::optional<std::string> optional_choice(const std::string& key,
                                             std::initializer_list<const char*> choices);
  std::string choice_or(const std::string& key, std::initializer_list<const char*> choices,
                        const std::string& fallback);

  YamlSection section(const std::string& key);
  std::optional<YamlSection> optional_section(const std::string& key);
  std::vector<YamlSection> section_list(const std::string& key);  // absent = empty

  // Refuses keys that were never read.
  void finish() const;

  // Refusals in the one format, at `key` of this section ("" = the section itself).
  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& expected) const;
  // Refuses `value` (read from `key`) outside [lo, hi]; `expected` says what the key is, e.g.
  // "an order", and the message adds the range.
  void require_within(const std::string& key, double value, double lo, double hi,
                      const std::string& expected) const;
  // The value of `key` as written (a list or mapping in flow style).
  std::string value_text(const std::string& key) const;

 private:
  YAML::Node get(const std::string& key);
  // The node of `key`, marked used, or nothing when absent; refuses a key without a value.
  std::optional<YAML::Node> present(const std::string& key, const std::string& expected);
  YAML::Node node_;
  std::string path_;
  std::string source_;
  std::set<std::string> used_;           // keys read
  mutable std::set<std::string> known_;  // keys the schema asked for, present or not (for hints)
};

// The mapping at the top of a parsed document; `expected` says what the document holds.
YamlSection document_section(const YAML::Node& root, const std::string& source,
                             const std::string& expected = "a mapping of keys to values");

// Stores an optional getter's value where the key was given, converted to the field's type
// (the getter has already checked its range); leaves the default otherwise.
template <typename T>
void set_if(const std::optional<long long>& v, T& out) {
  if (v) out = static_cast<T>(*v);
}
inline void set_if(const std::optional<double>& v, double& out) {
  if (v) out = *v;
}

}  // namespace wavebench::strict_yaml
