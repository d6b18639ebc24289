#include "wavebench/report/endurance_section.hpp"

#include <string>
#include <vector>

#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

namespace {
using nlohmann::json;

const json* array_at(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it != object.end() && it->is_array() ? &*it : nullptr;
}

HtmlCell text(std::string t) {
  HtmlCell c;
  c.text = std::move(t);
  return c;
}

HtmlCell cell(const json& row, const char* key, int decimals) {
  const auto v = number(row, key);
  return text(v ? fixed(*v, decimals) : "\u2013");
}

}  // namespace

const json* endurance_section(const json& results) {
  if (!results.is_object()) return nullptr;
  const auto it = results.find("endurance");
  return it != results.end() && it->is_object() ? &*it : nullptr;
}

HtmlTable endurance_trend_table(const json& endurance) {
  HtmlTable t;
  t.caption = "TE of each output revolution";
  t.header = {"revolution", "end [s]", "mean [arcsec]", "p2p [arcsec]", "RMS [arcsec]"};
  std::vector<int> orders;
  if (const json* o = array_at(endurance, "mesh_orders")) {
    for (const auto& v : *o) {
      if (v.is_number_integer()) orders.push_back(v.get<int>());
    }
  }
  for (const int order : orders) t.header.push_back("order " + std::to_string(order) + " [arcsec]");
  t.header.push_back("brake [\u00b0C]");
  const json* rows = array_at(endurance, "revolutions");
  if (!rows) return t;
  for (const auto& r : *rows) {
    if (!r.is_object()) continue;
    std::vector<HtmlCell> row{cell(r, "revolution", 0), cell(r, "t_end_s", 1),
                              cell(r, "mean_arcsec", 3), cell(r, "p2p_arcsec", 3),
                              cell(r, "rms_arcsec", 3)};
    const json* mesh = array_at(r, "mesh_arcsec");
    for (std::size_t k = 0; k < orders.size(); ++k) {
      const bool has = mesh && k < mesh->size() && (*mesh)[k].is_number();
      row.push_back(text(has ? fixed((*mesh)[k].get<double>(), 3) : "\u2013"));
    }
    row.push_back(cell(r, "brake_temperature_c", 1));
    if (const auto e = r.find("error"); e != r.end() && e->is_string()) {
      row[0].alert = true;
      row[0].text += " (" + e->get<std::string>() + ")";
    }
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::optional<Figure> endurance_trend_figure(const json& endurance, const json* twin_diagnosis) {
  const json* rows = array_at(endurance, "revolutions");
  if (!rows || rows->empty()) return std::nullopt;
  std::vector<double> rev, mean, p2p, rms, temp_rev, temp;
  std::vector<std::vector<double>> mesh;
  for (const auto& r : *rows) {
    const auto n = number(r, "revolution");
    if (!n || r.contains("error")) continue;
    rev.push_back(*n);
    mean.push_back(number(r, "mean_arcsec").value_or(0));
    p2p.push_back(number(r, "p2p_arcsec").value_or(0));
    rms.push_back(number(r, "rms_arcsec").value_or(0));
    if (const auto t = number(r, "brake_temperature_c")) {
      temp_rev.push_back(*n);
      temp.push_back(*t);
    }
    if (const json* m = array_at(r, "mesh_arcsec")) {
      if (mesh.size() < m->size()) mesh.resize(m->size());
      for (std::size_t k = 0; k < m->size(); ++k) {
        mesh[k].push_back((*m)[k].is_number() ? (*m)[k].get<double>() : 0.0);
      }
    }
  }
  if (rev.empty()) return std::nullopt;
  Figure fig(2, 2, "Endurance: trend per output revolution");
  auto& te = fig.axes(0, 0);
  te.title = "TE";
  te.x_label = "output revolution";
  te.y_label = "arcsec";
  te.line(rev, p2p, "p2p", palette(0))
      .line(rev, rms, "RMS", palette(1))
      .line(rev, mean, "mean", palette(2));
  auto& lines = fig.axes(0, 1);
  lines.title = "Mesh lines";
  lines.x_label = "output revolution";
  lines.y_label = "arcsec";
  const json* orders = array_at(endurance, "mesh_orders");
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    if (mesh[k].size() != rev.size()) continue;  // a row without its lines: not drawn
    std::string label = "line " + std::to_string(k + 1);
    if (orders && k < orders->size() && (*orders)[k].is_number_integer())
      label = "order " + std::to_string((*orders)[k].get<int>());
    lines.line(rev, mesh[k], label, palette(static_cast<int>(k)));
  }
  auto& brake = fig.axes(1, 0);
  brake.title = "Brake coil temperature";
  brake.x_label = "output revolution";
  brake.y_label = "\u00b0C";
  if (!temp.empty()) brake.line(temp_rev, temp, "at the revolution's end", palette(3));
  auto& twin = fig.axes(1, 1);
  twin.title = "Twin residual RMS per revolution";
  twin.x_label = "output revolution (from the run's start)";
  twin.y_label = "arcsec";
  if (twin_diagnosis) {
    std::vector<double> x, y;
    if (const json* revs = array_at(*twin_diagnosis, "revolutions")) {
      for (const auto& r : *revs) {
        const auto n = number(r, "revolution");
        const auto v = number(r, "residual_rms_arcsec");
        if (n && v) {
          x.push_back(*n);
          y.push_back(*v);
        }
      }
    }
    if (!x.empty()) twin.line(x, y, "measured \u2212 twin", palette(4));
  }
  return fig;
}

}  // namespace wavebench::report
