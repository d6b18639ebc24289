#include "wavebench/daemon/run_history_query.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <optional>
#include <stdexcept>

#include "wavebench/procedures/procedure_catalogue.hpp"

namespace wavebench::daemon {

namespace {

constexpr std::size_t kMaxFilterText = 256;
constexpr std::size_t kMaxSpecName = 64;
constexpr long long kMaxOffset = 1000000000;

[[noreturn]] void refuse(const std::string& key, const std::string& value,
                         const std::string& expected) {
  throw std::invalid_argument(key + ": got '" + value + "', expected " + expected);
}

long long integer(const std::string& key, const std::string& value, long long lo, long long hi) {
  long long v = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (value.empty() || ec != std::errc() || end != value.data() + value.size() || v < lo ||
      v > hi) {
    refuse(key, value, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
  }
  return v;
}

bool digits(const std::string& s, std::size_t at, std::size_t n) {
  if (at + n > s.size()) return false;
  return std::all_of(s.begin() + static_cast<long>(at), s.begin() + static_cast<long>(at + n),
                     [](char c) { return c >= '0' && c <= '9'; });
}

int number_at(const std::string& s, std::size_t at, std::size_t n) {
  return std::stoi(s.substr(at, n));
}

// A run id bound: the compact UTC time ("20261124", "20261124T103000", a whole run id), and
// whether it is a whole run id. Hand-written: std::chrono::parse is not in this libstdc++.
struct Bound {
  std::string prefix;
  bool whole_id = false;
};

Bound time_bound(const std::string& key, const std::string& v) {
  const std::string expected =
      "an ISO date (2026-11-24), an ISO UTC time (2026-11-24T10:30:00Z) or a run id "
      "(20261124T103000.123456Z)";
  // A run id: 20261124T103000.123456Z
  if (v.size() == 23 && digits(v, 0, 8) && v[8] == 'T' && digits(v, 9, 6) && v[15] == '.' &&
      digits(v, 16, 6) && v[22] == 'Z') {
    return {v, true};
  }
  if (v.size() < 10 || !digits(v, 0, 4) || v[4] != '-' || !digits(v, 5, 2) || v[7] != '-' ||
      !digits(v, 8, 2)) {
    refuse(key, v, expected);
  }
  const int month = number_at(v, 5, 2), day = number_at(v, 8, 2);
  if (month < 1 || month > 12 || day < 1 || day > 31) refuse(key, v, expected);
  std::string prefix = v.substr(0, 4) + v.substr(5, 2) + v.substr(8, 2);
  if (v.size() == 10) return {prefix, false};
  // T HH:MM[:SS][Z]
  std::string rest = v.substr(10);
  if (!rest.empty() && rest.back() == 'Z') rest.pop_back();
  const bool minutes = rest.size() == 6 && rest[0] == 'T' && digits(rest, 1, 2) && rest[3] == ':' &&
                       digits(rest, 4, 2);
  const bool seconds = rest.size() == 9 && rest[0] == 'T' && digits(rest, 1, 2) && rest[3] == ':' &&
                       digits(rest, 4, 2) && rest[6] == ':' && digits(rest, 7, 2);
  if (!minutes && !seconds) refuse(key, v, expected);
  const int h = number_at(rest, 1, 2), m = number_at(rest, 4, 2);
  const int s = seconds ? number_at(rest, 7, 2) : 0;
  if (h > 23 || m > 59 || s > 59) refuse(key, v, expected);
  prefix += "T" + rest.substr(1, 2) + rest.substr(4, 2) + (seconds ? rest.substr(7, 2) : "");
  return {prefix, false};
}

std::string text(const std::string& key, const std::string& value) {
  if (value.empty() || value.size() > kMaxFilterText) {
    refuse(key, value.substr(0, 40), "1 to " + std::to_string(kMaxFilterText) + " characters");
  }
  return value;
}

}  // namespace

storage::RunQuery parse_run_history_query(const std::map<std::string, std::string>& query) {
  storage::RunQuery q;
  q.limit = kDefaultHistoryLimit;
  std::optional<std::string> from_text, to_text;
  for (const auto& [key, value] : query) {
    if (key == "procedure") {
      const auto names = procedures::procedure_names();
      if (std::find(names.begin(), names.end(), value) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        refuse(key, value, "one of " + list);
      }
      q.procedure = value;
    } else if (key == "unit") {
      q.unit_serial_prefix = text(key, value);  // "0042" finds "0042-A"
    } else if (key == "spec") {
      const bool ok = !value.empty() && value.size() <= kMaxSpecName &&
                      std::all_of(value.begin(), value.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' ||
                               c == '_' || c == '-';
                      });
      if (!ok) refuse(key, value, "a spec name of 1 to 64 characters A-Z a-z 0-9 . _ -");
      q.spec = value;
    } else if (key == "verdict") {
      if (value == "pass") {
        q.verdict = storage::RunVerdict::kPass;
      } else if (value == "fail") {
        q.verdict = storage::RunVerdict::kFail;
      } else if (value == "undecided") {
        q.verdict = storage::RunVerdict::kUndecided;
      } else if (value == "none") {
        q.verdict = storage::RunVerdict::kNone;
      } else {
        refuse(key, value, "pass, fail, undecided or none");
      }
    } else if (key == "status") {
      try {
        q.status = storage::parse_run_status(value);
      } catch (const std::invalid_argument&) {
        refuse(key, value, "running, complete, aborted or incomplete");
      }
    } else if (key == "from") {
      q.from_id = time_bound(key, value).prefix;
      from_text = value;
    } else if (key == "to") {
      const auto b = time_bound(key, value);
      // Inclusive: every id that starts with the date or time sorts before it with '~' added.
      q.to_id = b.whole_id ? b.prefix : b.prefix + "~";
      to_text = value;
    } else if (key == "offset") {
      q.offset = static_cast<int>(integer(key, value, 0, kMaxOffset));
    } else if (key == "limit") {
      q.limit = static_cast<int>(integer(key, value, 1, kMaxHistoryLimit));
    } else {
      refuse(key, value,
             "a known filter: unit, procedure, spec, verdict, status, from, to, offset or limit "
             "(unknown filter)");
    }
  }
  if (q.from_id && q.to_id && *q.from_id > *q.to_id) {
    refuse("to", *to_text, "a time not before from '" + *from_text + "'");
  }
  return q;
}

nlohmann::json run_history_page(const storage::RunStore& store, const storage::RunQuery& query) {
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& run : store.list_runs(query)) runs.push_back(storage::to_json(run));
  return {{"runs", runs},
          {"total", store.count_runs(query)},
          {"offset", query.offset},
          {"limit", query.limit}};
}

}  // namespace wavebench::daemon
