#pragma once
// ISO 8601 times as the SQLite store keeps and compares them: one text form
// ("2026-11-24T10:15:00.000000Z", UTC, microseconds) that sorts as the times do, as PostgreSQL's
// timestamptz compares them.

#include <string>

namespace wavebench::fleet {

// "YYYY-MM-DD", optionally "T" or " " then "HH:MM[:SS[.fraction]]", optionally "Z" or an offset
// "+HH[:MM]" / "-HH[:MM]" within +-23:59 (none: UTC), as RFC 3339 bounds them: a leap second
// only at 23:59:60 UTC on June 30 or December 31 (kept as 23:59:59.999999), the result's year
// 1000..9999. Throws std::invalid_argument naming `key`, the value and the form expected.
std::string canonical_utc(const std::string& text, const std::string& key);

}  // namespace wavebench::fleet
