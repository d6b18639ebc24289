#pragma once
// Reads a procedure's options from JSON with messages that name the key, the value and what
// was expected; unknown keys are refused (a typo must not silently run the defaults).
//
// The same declarations describe the options: a reader made without options collects, for each
// call, the option's name, type, unit, default (the value it was handed), range and description
// (the schema the console's start form is generated from), so the parser and the schema cannot
// drift apart.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace wavebench::procedures {

// The unit ("rad/s", "N·m", "s", "rpm", "" for a count) and a one-line description of an option.
struct OptionDoc {
  const char* unit;
  const char* description;
};

// One option as the schema shows it.
struct OptionSpec {
  std::string name;
  std::string type;  // "number", "integer", "boolean" or "number_list"
  std::string unit;
  nlohmann::json default_value;
  std::optional<double> minimum, maximum;
  bool exclusive_minimum = false;
  std::optional<std::size_t> min_items, max_items;
  std::string description;

  // {name, type, unit, default, minimum, maximum, exclusive_minimum, min_items, max_items,
  // description}; an absent bound is left out.
  nlohmann::json to_json() const;
};

class OptionReader {
 public:
  // Parsing: `scope` prefixes keys in messages ("static", "dynamic", "lost-motion"); a key of
  // `options` that is not in `schema` is refused.
  OptionReader(const nlohmann::json& options, std::string scope,
               const std::vector<OptionSpec>& schema);
  // Describing: every call records its option and leaves the value untouched.
  explicit OptionReader(std::string scope);

  // Each leaves `value` untouched when the key is absent.
  void number(const char* key, double& value, double min, double max, bool min_inclusive,
              const OptionDoc& doc);
  void integer(const char* key, int& value, int min, int max, const OptionDoc& doc);
  void boolean(const char* key, bool& value, const OptionDoc& doc);
  // A list of min_count..max_count numbers; an element out of range is named by its index
  // ("static.loads_nm[1]: got '200', ...").
  void numbers(const char* key, std::vector<double>& values, double min, double max,
               bool min_inclusive, std::size_t min_count, const OptionDoc& doc,
               std::size_t max_count = kMaxListEntries);

  // What a describing reader collected, in declaration order.
  const std::vector<OptionSpec>& described() const { return described_; }

  // Every list option is bounded: each entry is a pass, a load step or a ladder rung, and a
  // request of thousands of them is a mistake, not a test plan.
  static constexpr std::size_t kMaxListEntries = 64;

 private:
  [[noreturn]] void fail(const std::string& key, const nlohmann::json& value,
                         const std::string& expected) const;
  // True when the key is to be parsed (parsing and present); records it when describing.
  bool wanted(OptionSpec spec);
  const nlohmann::json* options_ = nullptr;  // null: describing
  std::string scope_;
  std::vector<OptionSpec> described_;
};

}  // namespace wavebench::procedures
