#pragma once
// One mapping of a twin-case file with its key path ("te.terms[2]"). Every read marks its key
// as used; finish() then rejects whatever was not read, which is how typos get caught.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "wavebench/config/units.hpp"
#include "wavebench/model/gear_params.hpp"

namespace wavebench::config {

class YamlSection {
 public:
  YamlSection(YAML::Node node, std::string path);

  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const;
  bool has(const std::string& key) const;

  double quantity(const std::string& key, Dimension dimension);
  double quantity_or(const std::string& key, Dimension dimension, double fallback);
  std::optional<double> optional_quantity(const std::string& key, Dimension dimension);
  double positive_quantity(const std::string& key, Dimension dimension);  // required, > 0
  // Optional, >= 0 when given.
  double non_negative_quantity_or(const std::string& key, Dimension dimension, double fallback);
  std::vector<double> quantity_list(const std::string& key, Dimension dimension);

  int integer(const std::string& key);
  int integer_or(const std::string& key, int fallback);
  std::string text(const std::string& key);
  std::string text_or(const std::string& key, const std::string& fallback);
  bool boolean_or(const std::string& key, bool fallback);
  // One of `choices`; the error lists them.
  std::string choice(const std::string& key, std::initializer_list<const char*> choices);
  std::string choice_or(const std::string& key, std::initializer_list<const char*> choices,
                        const std::string& fallback);

  YamlSection section(const std::string& key);
  std::optional<YamlSection> optional_section(const std::string& key);
  std::vector<YamlSection> section_list(const std::string& key);  // absent = empty

  // A sinusoid: a plain quantity (the offset) or {offset, amplitude, frequency, phase}.
  model::Sinusoid sinusoid_or(const std::string& key, Dimension dimension);

  // Rejects keys that were never read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& expected) const;
  // Refuses `value` (read from `key`) outside [lo, hi]: the bounds that keep a run's memory
  // and time finite. `expected` says what the key is, e.g. "an order".
  void require_within(const std::string& key, double value, double lo, double hi,
                      const std::string& expected) const;
  std::string value_text(const std::string& key) const;

 private:
  YAML::Node get(const std::string& key);
  YAML::Node node_;
  std::string path_;
  std::set<std::string> used_;           // keys read
  mutable std::set<std::string> known_;  // keys the schema asked for, present or not (for hints)
};

// Physical bounds that keep a run finite: no gear turns its input faster (about 95 000 rpm),
// no excitation order or tooth count is larger, no sinusoid in a case is faster.
inline constexpr double kMaxSpeedRadS = 1e4;
inline constexpr double kMaxOrder = 1e4;
inline constexpr double kMaxSinusoidHz = 1e5;

// Lists longer than this are refused: no shipped case has more than a few dozen items, and a
// list's length multiplies the work of every step.
inline constexpr std::size_t kMaxListItems = 10000;

// The mapping at the top of a document.
YamlSection document_section(const YAML::Node& root);

}  // namespace wavebench::config
