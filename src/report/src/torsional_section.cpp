#include "wavebench/report/torsional_section.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "wavebench/metrology/gear_sense.hpp"
#include "wavebench/metrology/lost_motion_fit.hpp"

namespace wavebench::report {
namespace {

using nlohmann::json;

// The object at t[key] (or t[key][sub]), nullptr when absent or not an object.
const json* figure_at(const json& t, const char* key, const char* sub = nullptr) {
  if (!t.is_object()) return nullptr;
  const auto it = t.find(key);
  if (it == t.end() || !it->is_object()) return nullptr;
  return sub ? figure_at(*it, sub) : &*it;
}

// "0.351 ± 0.017", decimals < 0: significant digits.
std::string plus_minus(const json* figure, int decimals) {
  if (!figure) return "\u2013";
  const auto v = number(*figure, "value");
  if (!v) return "\u2013";
  const auto fmt = [&](double x) { return decimals >= 0 ? fixed(x, decimals) : general(x, 4); };
  std::string s = fmt(*v);
  if (const auto u = number(*figure, "expanded")) s += " \u00b1 " + fmt(*u);
  return s;
}

struct FigureKey {
  const char* label;
  const char* key;
  const char* sub;  // the figure's key within `key`, or nullptr
  const char* unit;
  int decimals;
};

const FigureKey kFigures[] = {
    {"hysteresis loss", "hysteresis_loss_arcmin", nullptr, "arcmin", 3},
    {"lost motion", "lost_motion_arcmin", nullptr, "arcmin", 3},
    {"backlash", "backlash_arcmin", nullptr, "arcmin", 3},
    {"K1", "stiffness", "k1_nm_per_rad", "N*m/rad", -1},
    {"K2", "stiffness", "k2_nm_per_rad", "N*m/rad", -1},
    {"K3", "stiffness", "k3_nm_per_rad", "N*m/rad", -1},
    {"T1", "stiffness", "t1_nm", "N*m", 2},
    {"T2", "stiffness", "t2_nm", "N*m", 2},
};

}  // namespace

const json* torsional_section(const json& results) {
  if (!results.is_object()) return nullptr;
  const auto it = results.find("torsional");
  return it != results.end() && it->is_object() ? &*it : nullptr;
}

HtmlTable torsional_table(bool with_run) {
  HtmlTable t;
  if (with_run) t.header.push_back("run");
  for (const auto& f : kFigures) t.header.push_back(std::string(f.label) + " [" + f.unit + "]");
  for (const char* h : {"lost motion at +/- [N*m]", "T_max [N*m]", "slipped points"}) {
    t.header.push_back(h);
  }
  t.caption = "Torsional stiffness, locked output (value +/- U, k = 2)";
  return t;
}

void add_torsional_rows(HtmlTable& table, const RunFolder& run, const RunCell& run_cell) {
  const json* t = torsional_section(run.results);
  if (!t) return;
  std::vector<HtmlCell> row;
  if (run_cell) row.push_back(*run_cell);
  for (const auto& f : kFigures)
    row.push_back({plus_minus(figure_at(*t, f.key, f.sub), f.decimals), {}, false});
  const auto at = number(*t, "lost_motion_torque_nm");
  const auto t_max = number(*t, "t_max_nm");
  const json* slip = figure_at(*t, "slip");
  const double slipped = slip ? number(*slip, "slipped_points").value_or(-1) : -1;
  row.push_back({at ? fixed(*at, 2) : "\u2013", {}, false});
  row.push_back({t_max ? fixed(*t_max, 1) : "\u2013", {}, false});
  row.push_back({slipped >= 0 ? fixed(slipped, 0) : "\u2013", {}, slipped > 0});
  table.rows.push_back(std::move(row));
}

HtmlTable torsional_budget_table() {
  HtmlTable t;
  t.header = {"figure", "contribution", "type", "standard uncertainty", "unit"};
  t.caption = "Uncertainty budget of the torsional figures (GUM; U = 2 u_c)";
  return t;
}

void add_torsional_budget_rows(HtmlTable& table, const RunFolder& run) {
  const json* t = torsional_section(run.results);
  if (!t) return;
  for (const auto& f : kFigures) {
    const json* fig = figure_at(*t, f.key, f.sub);
    if (!fig) continue;
    const auto budget = fig->find("budget");
    if (budget == fig->end() || !budget->is_array()) continue;
    for (const auto& c : *budget) {
      if (!c.is_object()) continue;
      const auto u = number(c, "standard");
      table.rows.push_back({{f.label, {}, false},
                            {c.value("source", std::string("\u2013")), {}, false},
                            {c.value("type", std::string("\u2013")), {}, false},
                            {u ? general(*u, 3) : "\u2013", {}, false},
                            {f.unit, {}, false}});
    }
    const auto u = number(*fig, "expanded");
    table.rows.push_back({{f.label, {}, false},
                          {"expanded (k = 2)", {}, false},
                          {"", {}, false},
                          {u ? general(*u, 3) : "\u2013", {}, false},
                          {f.unit, {}, false}});
  }
}

std::optional<Figure> torsional_loop_figure(const json& t) {
  const auto pts = t.find("points");
  if (pts == t.end() || !pts->is_array() || pts->size() < 2) return std::nullopt;
  Figure fig(1, 1, "Torsional stiffness, locked output");
  Axes& ax = fig.axes(0, 0);
  ax.title = "Torsion angle against torque (catalogue view)";
  ax.x_label = "torque [N*m]";
  ax.y_label = "twist theta_in/N - theta_out [arcmin]";
  struct Branch {
    const char* key;
    const char* label;
    int colour;
    std::vector<double> x, y;
  } branches[] = {{"first_loading", "first loading", 0, {}, {}},
                  {"unloading", "unloading", 1, {}, {}},
                  {"reloading", "reloading", 2, {}, {}}};
  std::vector<double> vx, vy;
  for (const auto& p : *pts) {
    const auto torque = number(p, "torque_nm");
    const auto twist = number(p, "twist_arcmin");
    if (!torque || !twist) continue;
    if (p.value("voided", false)) {
      vx.push_back(*torque);
      vy.push_back(*twist);
      continue;
    }
    const std::string branch = p.value("branch", std::string());
    for (auto& b : branches) {
      if (branch == b.key) {
        b.x.push_back(*torque);
        b.y.push_back(*twist);
      }
    }
  }
  for (auto& b : branches) {
    if (b.x.empty()) continue;
    ax.line(b.x, b.y, {}, palette(b.colour));
    ax.scatter(std::move(b.x), std::move(b.y), b.label, palette(b.colour), 2.2);
  }
  if (!vx.empty()) ax.scatter(vx, vy, "voided (output slipped)", palette(6), 3.5);

  // The fitted three-segment curve as results.json carries it (each side of zero at its own
  // offset, computed once by the procedure): drawn, not recomputed.
  if (const auto c = t.find("fit_curve"); c != t.end() && c->is_array()) {
    bool first = true;
    for (const auto& side : *c) {
      if (!side.is_object()) continue;
      std::vector<double> fx, fy;
      const auto& ts = side.value("torque_nm", json::array());
      const auto& ys = side.value("twist_arcmin", json::array());
      for (std::size_t i = 0; i < std::min(ts.size(), ys.size()); ++i) {
        if (!ts[i].is_number() || !ys[i].is_number()) continue;
        fx.push_back(ts[i].get<double>());
        fy.push_back(ys[i].get<double>());
      }
      if (fx.empty()) continue;
      ax.line(std::move(fx), std::move(fy), first ? "fit K1/K2/K3 (mean curve)" : "", palette(3))
          .series.back()
          .width = 2.2;
      first = false;
    }
  }
  const auto note = [&](const char* key, const char* what, double y) {
    if (const json* f = figure_at(t, key)) {
      ax.annotate(0, y, std::string(what) + " " + plus_minus(f, 3) + " arcmin", false);
    }
  };
  double y_top = 0, y_bottom = 0;
  for (const auto& p : *pts) {
    if (const auto y = number(p, "twist_arcmin")) {
      y_top = std::max(y_top, *y);
      y_bottom = std::min(y_bottom, *y);
    }
  }
  note("hysteresis_loss_arcmin", "hysteresis loss", y_top);
  note("lost_motion_arcmin", "lost motion", y_top - 0.08 * (y_top - y_bottom));
  return fig;
}

}  // namespace wavebench::report
