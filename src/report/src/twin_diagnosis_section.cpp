#include "wavebench/report/twin_diagnosis_section.hpp"

#include <string>
#include <utility>

namespace wavebench::report {
namespace {

using nlohmann::json;

double number(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : 0.0;
}

std::string text(const json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

HtmlCell cell(std::string value, bool alert = false) {
  return {std::move(value), {}, alert};
}

std::string first_source(const json& flag) {
  const auto it = flag.find("sources");
  if (it == flag.end() || !it->is_array() || it->empty()) return "none of the model's lines";
  const json& s = it->front();
  std::string out = text(s, "source") + " [" + text(s, "family") + "]";
  if (number(s, "harmonic") > 1) out += ", harmonic " + fixed(number(s, "harmonic"), 0);
  return out;
}

}  // namespace

void add_twin_diagnosis_section(HtmlPage& page, const RunFolder& run) {
  const auto twin = run.results.find("twin");
  if (twin == run.results.end() || !twin->is_object()) return;
  const auto diagnosis = twin->find("diagnosis");
  if (diagnosis == twin->end() || !diagnosis->is_object()) return;
  const json& revolutions = diagnosis->value("revolutions", json::array());
  const json& flags = diagnosis->value("flags", json::array());
  page.heading("The twin's diagnosis");
  const json& band = diagnosis->value("band", json::object());
  page.paragraph(
      "The residual (measured − predicted TE) of each whole output revolution against its "
      "expected band: the larger of the sensor floor, " +
      fixed(number(band, "noise_factor"), 0) + "× the revolution's median line and " +
      fixed(100 * number(band, "relative_band"), 0) + " % of the twin's own line at that order. " +
      std::to_string(revolutions.size()) + " revolutions analysed.");
  if (flags.empty()) {
    double largest = 0, order = 0;
    for (const auto& r : revolutions) {
      if (number(r, "largest_ratio") > largest) {
        largest = number(r, "largest_ratio");
        order = number(r, "largest_ratio_order");
      }
    }
    page.paragraph(revolutions.empty()
                       ? "No whole output revolution turning one way: nothing to watch."
                       : "No flag: no line left its band (the largest reached " +
                             fixed(largest, 2) + "× its band, at order " + fixed(order, 0) + ").");
    return;
  }
  HtmlTable table;
  table.caption = "Lines of the residual above their band";
  table.header = {"order",
                  "residual [arcsec]",
                  "band [arcsec]",
                  "first revolution",
                  "flagged at [s]",
                  "revolutions",
                  "ranked first by the twin",
                  "suspect"};
  for (const auto& f : flags) {
    table.rows.push_back(
        {cell(fixed(number(f, "order"), 0), true), cell(fixed(number(f, "amplitude_arcsec"), 2)),
         cell(fixed(number(f, "band_arcsec"), 2)), cell(fixed(number(f, "first_revolution"), 0)),
         cell(fixed(number(f, "flagged_s"), 1)), cell(fixed(number(f, "revolutions"), 0)),
         cell(first_source(f)), cell(text(f, "suspect"))});
  }
  page.table(table);
}

}  // namespace wavebench::report
