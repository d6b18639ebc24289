// The CiA 306 line reader. General INI parsers do not fit: CiA 306 keys and section names are
// case-insensitive, ';' starts a comment line, vendor files repeat keys and sections, and
// values (VISIBLE_STRING defaults) hold '=' and ';' that must stay.
#include <fmt/format.h>

#include "eds_detail.hpp"
#include "wavebench/canopen/eds.hpp"

namespace wavebench::canopen::eds_detail {

const IniKey* IniSection::get(std::string_view key) const {
  const auto it = keys.find(lower(key));
  return it == keys.end() ? nullptr : &it->second;
}

const IniSection* IniFile::get(std::string_view name) const {
  const auto it = by_name.find(lower(name));
  return it == by_name.end() ? nullptr : &sections[it->second];
}

IniFile read_ini(std::string_view text, const IniLimits& limits, Warnings& warnings) {
  IniFile file;
  IniSection* current = nullptr;  // nullptr before the first section and inside a duplicate
  bool in_duplicate = false;
  std::size_t keys = 0;
  std::size_t number = 0;
  while (!text.empty()) {
    ++number;
    const auto end = text.find('\n');
    const auto raw = text.substr(0, end);
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
    if (raw.size() > limits.max_line_bytes)
      throw EdsError(fmt::format("EDS {}: line {}: {} bytes: expected at most {} bytes a line",
                                 warnings.source(), number, raw.size(), limits.max_line_bytes));
    const auto line = trim(raw);  // also drops the '\r' of CRLF
    if (line.empty() || line.front() == ';' || line.front() == '#') continue;
    if (line.front() == '[') {
      const auto close = line.find(']');
      const auto after = close == std::string_view::npos ? line : trim(line.substr(close + 1));
      if (close == std::string_view::npos || (!after.empty() && after.front() != ';')) {
        warnings.line(
            number, fmt::format("'{}': expected [section name]; the line is ignored", clip(line)));
        continue;
      }
      const auto name = trim(line.substr(1, close - 1));
      const auto [at, added] = file.by_name.emplace(lower(name), file.sections.size());
      if (!added) {
        warnings.line(number, fmt::format("[{}] appears again (first on line {}; section names are "
                                          "case-insensitive): the first is used",
                                          clip(name), file.sections[at->second].line));
        current = nullptr;
        in_duplicate = true;
        continue;
      }
      if (file.sections.size() >= limits.max_sections)
        throw EdsError(fmt::format("EDS {}: line {}: more than {} sections", warnings.source(),
                                   number, limits.max_sections));
      file.sections.push_back({std::string(name), number, {}});
      current = &file.sections.back();
      in_duplicate = false;
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string_view::npos || trim(line.substr(0, eq)).empty()) {
      warnings.line(number, fmt::format("'{}': expected Key=Value, [section] or a ; comment; "
                                        "the line is ignored",
                                        clip(line)));
      continue;
    }
    if (in_duplicate) continue;  // said once, at the section's name
    const auto key = trim(line.substr(0, eq));
    const auto value = trim(line.substr(eq + 1));
    if (!current) {
      warnings.line(number, fmt::format("{} outside any section; ignored", clip(key)));
      continue;
    }
    if (++keys > limits.max_keys)
      throw EdsError(fmt::format("EDS {}: line {}: more than {} keys", warnings.source(), number,
                                 limits.max_keys));
    const auto [at, added] =
        current->keys.emplace(lower(key), IniKey{std::string(key), std::string(value), number});
    if (!added) {
      warnings.value(current->name, key, value,
                     fmt::format("each key once (keys are case-insensitive; line {} is used, "
                                 "line {} ignored)",
                                 at->second.line, number));
    }
  }
  return file;
}

}  // namespace wavebench::canopen::eds_detail
