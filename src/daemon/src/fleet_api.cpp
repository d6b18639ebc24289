#include "wavebench/daemon/fleet_api.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"
#include "wavebench/fleet/utc_time_text.hpp"

namespace wavebench::daemon {

namespace {

struct BadQuery : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

std::optional<std::string> text(const HttpTarget& t, const std::string& key) {
  const auto it = t.query.find(key);
  if (it == t.query.end() || it->second.empty()) return std::nullopt;
  return it->second;
}

std::optional<double> number(const HttpTarget& t, const std::string& key) {
  const auto value = text(t, key);
  if (!value) return std::nullopt;
  double v = 0;
  const auto [end, ec] = std::from_chars(value->data(), value->data() + value->size(), v);
  // from_chars reads "nan" and "inf" too: a limit, a load or a count is a finite number.
  if (ec != std::errc() || end != value->data() + value->size() || !std::isfinite(v)) {
    throw BadQuery(key + ": got '" + *value + "', expected a finite number");
  }
  return v;
}

// One of `allowed` (compared without case; the answer has the allowed spelling), or nothing.
std::optional<std::string> choice(const HttpTarget& t, const std::string& key,
                                  const std::vector<std::string>& allowed) {
  const auto value = text(t, key);
  if (!value) return std::nullopt;
  const auto same = [&](const std::string& a) {
    return std::equal(a.begin(), a.end(), value->begin(), value->end(), [](char x, char y) {
      return std::tolower(static_cast<unsigned char>(x)) ==
             std::tolower(static_cast<unsigned char>(y));
    });
  };
  const auto it = std::find_if(allowed.begin(), allowed.end(), same);
  if (it != allowed.end()) return *it;
  std::string list;
  for (std::size_t i = 0; i < allowed.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == allowed.size() ? " or " : ", ") + allowed[i];
  }
  throw BadQuery(key + ": got '" + *value + "', expected " + list);
}

// The keys each query takes: any other is refused, so a typo never returns an unfiltered answer.
const std::map<std::string, std::vector<std::string>>& known_keys() {
  static const std::map<std::string, std::vector<std::string>> keys = {
      {"figures", {}},
      {"runs", {"model", "bench", "unit", "procedure", "verdict", "from", "to", "limit"}},
      {"trend", {"figure", "model", "bench", "direction", "load", "from", "to", "last"}},
      {"spc",
       {"figure", "model", "bench", "direction", "load", "from", "to", "last", "lsl", "usl"}},
  };
  return keys;
}

void refuse_unknown_keys(const HttpTarget& t, const std::vector<std::string>& keys) {
  std::string unknown;
  for (const auto& [key, value] : t.query) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      unknown += (unknown.empty() ? "'" : ", '") + key + "'";
    }
  }
  if (unknown.empty()) return;
  std::string list;
  for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
  throw BadQuery("unknown parameter " + unknown + " for /api/fleet/" + t.segments.at(2) +
                 "; expected " + (list.empty() ? std::string("none") : list));
}

// Checked before a store is opened (the store canonicalises them again): a bad time is 400,
// not an unreachable store's 503.
void check_utc_time(const HttpTarget& t, const std::string& key) {
  if (const auto value = text(t, key)) (void)fleet::canonical_utc(*value, key);
}

int count(const HttpTarget& t, const std::string& key, int fallback, int most) {
  const auto value = number(t, key);
  if (!value) return fallback;
  if (*value < 0 || *value > most || *value != static_cast<int>(*value)) {
    throw BadQuery(key + ": got '" + *text(t, key) + "', expected an integer 0.." +
                   std::to_string(most));
  }
  return static_cast<int>(*value);
}

fleet::FigureQuery figure_query(const HttpTarget& t) {
  fleet::FigureQuery q;
  const auto figure = text(t, "figure");
  const auto model = text(t, "model");
  if (!figure) throw BadQuery("figure: missing, expected a figure name (e.g. static_te_p2p)");
  if (!model) throw BadQuery("model: missing, expected the gear model");
  q.figure = *figure;
  q.gear_model = *model;
  q.bench = text(t, "bench");
  q.direction = choice(t, "direction", {"forward", "reverse"});
  q.load_nm = number(t, "load");
  q.from = text(t, "from");
  q.to = text(t, "to");
  q.last = count(t, "last", 0, 1000000);
  return q;
}

// The figures a trend may name, for the console's fleet page (no store needed).
ApiResponse figures() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& f : fleet::fleet_figures()) {
    list.push_back({{"name", f.name},
                    {"unit", f.unit},
                    {"what", f.what},
                    {"has_spec_limit", *f.limit_key != '\0'},
                    {"limit_is_minimum", f.limit_is_minimum}});
  }
  return {200, {{"figures", list}}};
}

ApiResponse answer(fleet::ResultsStore& store, const HttpTarget& t) {
  const std::string& what = t.segments.at(2);
  if (what == "runs") {
    fleet::FleetRunQuery q;
    q.gear_model = text(t, "model");
    q.bench = text(t, "bench");
    q.unit_serial_prefix = text(t, "unit");  // "0042" finds "0042-A", as the history does
    q.procedure = text(t, "procedure");
    q.verdict = choice(t, "verdict", {"PASS", "FAIL", "UNDECIDED"});
    q.from = text(t, "from");
    q.to = text(t, "to");
    q.limit = count(t, "limit", 50, 10000);
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& r : store.runs(q)) runs.push_back(fleet::to_json(r));
    return {200, {{"runs", runs}}};
  }
  if (what == "trend") {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : store.trend(figure_query(t))) points.push_back(fleet::to_json(p));
    return {200, {{"points", points}}};
  }
  if (what == "spc") {
    const auto lsl = number(t, "lsl");
    const auto usl = number(t, "usl");
    if (lsl && usl && !(*lsl < *usl)) {
      throw BadQuery("lsl: got '" + *text(t, "lsl") + "', expected below usl (" + *text(t, "usl") +
                     ")");
    }
    return {200, fleet::to_json(store.spc(figure_query(t), {lsl, usl}))};
  }
  return api_error(404, "not found",
                   "no resource at " + t.path + "; expected runs, trend, spc or figures");
}

}  // namespace

FleetQueries make_fleet_queries(fleet::ResultsConfig config, std::filesystem::path own_index) {
  return [config = std::move(config),
          own_index = std::move(own_index)](const HttpTarget& target) -> ApiResponse {
    if (target.segments.size() != 3 || !known_keys().contains(target.segments[2])) {
      return api_error(404, "not found",
                       "no resource at " + target.path + "; expected runs, trend, spc or figures");
    }
    try {
      refuse_unknown_keys(target, known_keys().at(target.segments[2]));
      if (target.segments[2] != "figures") {
        check_utc_time(target, "from");
        check_utc_time(target, "to");
      }
    } catch (const std::invalid_argument& e) {
      return api_error(400, "bad request", e.what());
    }
    if (target.segments[2] == "figures") return figures();
    std::unique_ptr<fleet::ResultsStore> store;
    try {
      if (config.shared()) {
        store = std::make_unique<fleet::PostgresResultsStore>(config);
      } else {
        // Read only: a query never takes the index's write lock (the run store's and the
        // outbox's writes go on). Read-write only before the outbox has made the tables.
        try {
          store = std::make_unique<fleet::SqliteResultsStore>(
              own_index, fleet::SqliteResultsStore::Access::kReadOnly);
        } catch (const std::exception&) {
          store = std::make_unique<fleet::SqliteResultsStore>(own_index);
        }
      }
    } catch (const std::exception& e) {
      return api_error(503, "results store unreachable", e.what());
    }
    try {
      return answer(*store, target);
    } catch (const std::invalid_argument& e) {  // BadQuery, and the store's own refusals
      return api_error(400, "bad request", e.what());
    } catch (const std::exception& e) {
      return api_error(503, "results store", e.what());
    }
  };
}

}  // namespace wavebench::daemon
