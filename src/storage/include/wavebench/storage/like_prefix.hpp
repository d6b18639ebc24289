#pragma once
// A prefix filter as an SQL LIKE pattern, for SQLite and PostgreSQL alike: the text's own
// wildcards (% and _) and the escape character are escaped, so "0042_" finds "0042_A" and not
// "0042-A". Use it with `column LIKE ? ESCAPE '\'` (SQLite's LIKE ignores ASCII case;
// where PostgreSQL reads it too, compare UPPER() of both sides to get the same answer).

#include <string>
#include <string_view>

namespace wavebench::storage {

inline constexpr const char* kLikeEscapeClause = " ESCAPE '\\'";

inline std::string like_prefix_pattern(std::string_view text) {
  std::string pattern;
  pattern.reserve(text.size() + 8);
  for (const char c : text) {
    if (c == '\\' || c == '%' || c == '_') pattern += '\\';
    pattern += c;
  }
  pattern += '%';
  return pattern;
}

}  // namespace wavebench::storage
