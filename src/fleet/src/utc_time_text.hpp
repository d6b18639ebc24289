#pragma once
// ISO 8601 times as the SQLite store keeps and compares them: one text form
// ("2026-11-24T10:15:00.000000Z", UTC, microseconds) that sorts as the times do, as PostgreSQL's
// timestamptz compares them.

#include <string>

namespace wavebench::fleet {

// "YYYY-MM-DD", optionally "T" or " " then "HH:MM[:SS[.fraction]]", optionally "Z" or an offset
// "+HH[:MM]" / "-HH[:MM]" (none: UTC). Throws std::invalid_argument naming `key`, the value and
// the form expected.
std::string canonical_utc(const std::string& text, const std::string& key);

}  // namespace wavebench::fleet
