#pragma once
// Reads a procedure's options from JSON with messages that name the key, the value and what
// was expected; unknown keys are refused (a typo must not silently run the defaults).

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace wavebench::runs {

class OptionReader {
 public:
  // `scope` prefixes keys in messages ("static", "dynamic", "lost-motion").
  OptionReader(const nlohmann::json& options, std::string scope,
               std::initializer_list<const char*> known_keys);

  // Each leaves `value` untouched when the key is absent.
  void number(const char* key, double& value, double min, double max, bool min_inclusive = true);
  void integer(const char* key, int& value, int min, int max);
  void boolean(const char* key, bool& value);
  // A list of min_count..max_count numbers; an element out of range is named by its index
  // ("static.loads_nm[1]: got '200', ...").
  void numbers(const char* key, std::vector<double>& values, double min, double max,
               std::size_t min_count, std::size_t max_count = kMaxListEntries);

  // Every list option is bounded: each entry is a pass, a load step or a ladder rung, and a
  // request of thousands of them is a mistake, not a test plan.
  static constexpr std::size_t kMaxListEntries = 64;

 private:
  [[noreturn]] void fail(const std::string& key, const nlohmann::json& value,
                         const std::string& expected) const;
  const nlohmann::json& options_;
  std::string scope_;
};

}  // namespace wavebench::runs
