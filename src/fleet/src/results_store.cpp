#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet {

namespace {

nlohmann::json text_or_null(const std::string& text) {
  return text.empty() ? nlohmann::json(nullptr) : nlohmann::json(text);
}

}  // namespace

nlohmann::json to_json(const FleetRunRow& r) {
  return {{"bench", r.bench},
          {"run_id", r.run_id},
          {"station", text_or_null(r.station)},
          {"operator", text_or_null(r.operator_name)},
          {"unit_serial", r.unit_serial},
          {"gear_model", text_or_null(r.gear_model)},
          {"spec", text_or_null(r.spec)},
          {"spec_version", text_or_null(r.spec_version)},
          {"procedure", r.procedure},
          {"status", r.status},
          {"verdict", text_or_null(r.verdict)},
          {"started_at", r.started_at},
          {"finished_at", text_or_null(r.finished_at)},
          {"software_version", r.software_version},
          {"samples_ref", r.samples_ref},
          {"figures", r.figures}};
}

nlohmann::json to_json(const TrendPoint& p) {
  return {{"sequence", p.sequence}, {"started_at", p.started_at},   {"bench", p.bench},
          {"run_id", p.run_id},     {"unit_serial", p.unit_serial}, {"value", p.value}};
}

nlohmann::json to_json(const SpcAnswer& a) {
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : a.points) points.push_back(to_json(p));
  const auto opt = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json j = {{"limits", {{"lower", opt(a.limits.lower)}, {"upper", opt(a.limits.upper)}}},
                      {"limits_from", a.limits_from},
                      {"points", points}};
  j["spc"] = a.points.size() >= 2 ? to_json(a.figures) : nlohmann::json(nullptr);
  return j;
}

}  // namespace wavebench::fleet
