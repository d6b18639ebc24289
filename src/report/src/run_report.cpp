#include "wavebench/report/run_report.hpp"

#include <algorithm>
#include <stdexcept>

#include "wavebench/analysis/amplitude_spectrum.hpp"
#include "wavebench/report/declared_figures_table.hpp"
#include "wavebench/report/dynamic_plot_data.hpp"
#include "wavebench/report/endurance_section.hpp"
#include "wavebench/report/run_plots.hpp"
#include "wavebench/report/run_tables.hpp"
#include "wavebench/report/torsional_section.hpp"
#include "wavebench/report/twin_diagnosis_section.hpp"
#include "wavebench/storage/atomic_file.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A plot goes to a temporary name first so that a crash leaves no truncated PNG under the
// name the page links.
fs::path write_plot(const Figure& fig, const fs::path& dir, const std::string& name, int height) {
  const fs::path target = dir / name;
  const fs::path tmp = dir / ("." + name + ".tmp");
  fig.write_png(tmp, 1400, height);
  fs::rename(tmp, target);
  return target;
}

void add_table(HtmlPage& page, const HtmlTable& table) {
  if (!table.rows.empty()) page.table(table);
}

std::string short_hash(const std::string& hash) {
  return hash.size() > 16 ? hash.substr(0, 16) + "\u2026" : hash;
}

std::string sample_facts(const SampleLogFacts& log) {
  return std::to_string(log.records) + " SYNC samples, " + std::to_string(log.missed) +
         " cycles missed, " + std::to_string(log.incomplete) + " incomplete";
}

// "forward 60 N*m", "mesh": what an entry of a figure group is, from whichever of its
// direction, name and load it has (malformed values are left out, not thrown over).
std::string budget_label(const json& entry) {
  std::string label;
  for (const char* key : {"direction", "name"}) {
    if (const auto it = entry.find(key); it != entry.end() && it->is_string()) {
      label += (label.empty() ? "" : " ") + it->get<std::string>();
    }
  }
  if (const auto load = number(entry, "load_nm")) label += " " + general(*load) + " N*m";
  return label;
}

}  // namespace

RunReport write_run_report(const fs::path& run_dir, const fs::path& out_dir) {
  RunFolder run = read_run_folder(run_dir);
  const fs::path out = out_dir.empty() ? run_dir : out_dir;
  fs::create_directories(out);
  RunReport report;
  analysis::SpectrumAnalyser analyser;

  HtmlPage page("Run " + run.run_id());
  std::vector<std::pair<std::string, HtmlCell>> facts = {
      {"run id", {run.run_id(), {}, false}},
      {"procedure", {run.field("procedure", "\u2013"), {}, false}},
      {"unit serial", {run.field("unit_serial", "\u2013"), {}, false}},
      {"status", status_cell(run)},
  };
  if (const auto v = run.results.find("verdict"); v != run.results.end() && v->is_string()) {
    std::string shown = v->get<std::string>();
    if (shown == "UNDECIDED") {
      const auto it = run.results.find("undecided_counts_as");
      const std::string counts =
          it != run.results.end() && it->is_string() ? it->get<std::string>() : "fail";
      shown += counts == "undecided" ? " (no acceptance decision)"
                                     : " (counts as " + counts + " for acceptance)";
    }
    facts.push_back({"verdict", {shown, {}, v->get<std::string>() != "PASS"}});
  }
  if (const std::string pass = run.field("pass"); !pass.empty() && pass != "null") {
    facts.push_back({"pass", {pass, {}, pass == "false"}});
  }
  // To the second: the stored times carry microseconds no reader of a report needs.
  const auto to_second = [](std::string t) {
    if (t.size() >= 19 && t[10] == 'T') t = t.substr(0, 10) + " " + t.substr(11, 8);
    return t;
  };
  facts.push_back({"started / finished (UTC)",
                   {to_second(run.field("started_at", "\u2013")) + " / " +
                        to_second(run.field("finished_at", "\u2013")),
                    {},
                    false}});
  facts.push_back({"software version", {run.field("software_version", "\u2013"), {}, false}});
  facts.push_back({"config hash", {short_hash(run.field("config_hash", "\u2013")), {}, false}});
  const bool have_samples = run.sample_log && run.sample_log->records > 0;
  if (have_samples) facts.push_back({"samples", {sample_facts(*run.sample_log), {}, false}});
  if (run.sense) {
    facts.push_back({"gear ratio N, output sign",
                     {general(run.sense->ratio) + ", " + std::to_string(run.sense->direction_sign) +
                          (run.sense_estimated ? " (estimated from the samples)" : ""),
                      {},
                      false}});
  }
  page.facts(facts);
  const std::string status = run.field("status");
  if (status == "aborted" || status == "incomplete") {
    const std::string reason = run.field("reason", "no reason recorded");
    page.paragraph("Run " + status + ": " + reason, true);
  }
  HtmlTable limits = limits_table();
  add_limit_rows(limits, run);
  add_table(page, limits);
  add_table(page, declared_figures_table(run.field("procedure"), run.results));

  // Static TE.
  if (const json* passes = static_passes(run.results)) {
    page.heading("Static TE");
    HtmlTable t = static_te_table(false);
    add_static_te_rows(t, run, std::nullopt);
    add_table(page, t);
    if (auto fig = static_te_figure(*passes)) {
      const int rows = fig->rows();
      report.plots.push_back(write_plot(*fig, out, "static_te.png", 260 + 340 * rows));
      page.image("static_te.png", "Static TE against output angle");
    }
    HtmlTable lm = static_lost_motion_table(false);
    add_static_lost_motion_rows(lm, run, std::nullopt);
    add_table(page, lm);
    HtmlTable shift = load_shift_table(false);
    add_load_shift_rows(shift, run, std::nullopt);
    add_table(page, shift);
    HtmlTable budget = budget_table("static TE");
    for (const auto& p : *passes) {
      if (!p.is_object()) continue;
      add_budget_rows(budget, p, budget_label(p));
    }
    add_table(page, budget);
    HtmlTable lm_budget = budget_table("lost motion and load shift (static)");
    if (const json* profiles = lost_motion_profiles(run.results)) {
      for (const auto& p : *profiles) {
        if (!p.is_object()) continue;
        add_budget_rows(lm_budget, p, "lost motion" + budget_label(p));
      }
    }
    if (const json* shifts = load_shifts(run.results)) {
      for (const auto& p : *shifts) {
        if (!p.is_object()) continue;
        add_budget_rows(lm_budget, p, budget_label(p));
      }
    }
    add_table(page, lm_budget);
  }

  // Dynamic TE.
  if (const json* dyn = dynamic_section(run.results)) {
    page.heading("Dynamic TE");
    HtmlTable t = dynamic_te_table(false);
    add_dynamic_te_rows(t, run, std::nullopt);
    add_table(page, t);
    // The analysed trace from the results when they carry it; the steady part of the
    // samples otherwise. The spectrum in Hz wants every sample when there are samples.
    const double ratio = run.sense ? run.sense->ratio : 0;
    std::optional<DynamicPlotData> analysed, recorded;
    if (const auto carried = dynamic_trace(*dyn)) {
      analysed = reduce_dynamic_trace(*carried, ratio, kEnvelopeColumns, analyser);
      // A long run's trace is already the min/max of blocks of its samples: the envelope is of
      // the record's samples, not of the trace's points (the plot's title counts them).
      const json* trace = dyn->contains("trace") ? &(*dyn)["trace"] : nullptr;
      if (trace && trace->is_object() && trace->value("samples_per_block", 1) > 1 &&
          dyn->contains("samples") && (*dyn)["samples"].is_number_unsigned()) {
        const auto samples = (*dyn)["samples"].get<std::size_t>();
        for (auto* d : {&analysed->te_by_angle, &analysed->te_by_time}) {
          d->samples_in_range = samples;
          d->full_resolution = false;
        }
      }
    }
    if (run.sense && have_samples) {
      try {
        recorded = dynamic_plot_data(run.samples_path(), *run.sample_log, *run.sense,
                                     kEnvelopeColumns, analyser);
      } catch (const std::exception& e) {  // changed since it was first read
        run.notes.push_back(std::string("samples.wbs unreadable for the TE plots: ") + e.what());
      }
    }
    if (const auto& shown = analysed ? analysed : recorded) {
      if (auto fig = dynamic_te_figure(*shown)) {
        report.plots.push_back(write_plot(*fig, out, "dynamic_te.png", 900));
        page.image("dynamic_te.png", "Dynamic TE against output angle and time");
      }
    }
    const auto& spectral = recorded ? recorded : analysed;
    if (auto fig = dynamic_spectrum_figure(spectral ? &*spectral : nullptr, *dyn, ratio)) {
      report.plots.push_back(write_plot(*fig, out, "spectrum.png", 900));
      page.image("spectrum.png", "Dynamic TE spectrum with named peaks");
    }
    HtmlTable peaks = peaks_table();
    add_peak_rows(peaks, run);
    add_table(page, peaks);
    HtmlTable aliased = aliased_table();
    add_aliased_rows(aliased, run);
    add_table(page, aliased);
    HtmlTable budget = budget_table("dynamic TE");
    add_budget_rows(budget, *dyn, "");
    if (const auto lines = dyn->find("peaks"); lines != dyn->end() && lines->is_array()) {
      for (const auto& p : *lines) {
        if (p.is_object()) add_budget_rows(budget, p, budget_label(p));
      }
    }
    add_table(page, budget);
  }

  // Lost motion, hysteresis, stiffness.
  const json* fit = lost_motion_fit(run.results);
  if (fit) {
    page.heading("Lost motion, hysteresis and stiffness");
    HtmlTable t = stiffness_table(false);
    add_stiffness_rows(t, run, std::nullopt);
    add_table(page, t);
    HtmlTable budget = budget_table("lost motion and stiffness");
    add_budget_rows(budget, *fit, "");
    if (const auto k = fit->find("stiffness"); k != fit->end()) add_budget_rows(budget, *k, "");
    add_table(page, budget);
  }
  std::optional<TorqueTwistCurve> curve;
  if (fit) curve = torque_twist_from_results(*fit);
  if (!curve && (fit || run.field("procedure") == "lost-motion") && run.sense) {
    if (have_samples) {
      try {
        curve = torque_twist_from_log(run.samples_path(), run.sample_log->records, *run.sense);
      } catch (const std::exception& e) {
        run.notes.push_back(std::string("samples.wbs unreadable for the torque-twist plot: ") +
                            e.what());
      }
    }
  }
  if (curve) {
    if (auto fig = hysteresis_figure(*curve, fit)) {
      if (!fit) page.heading("Lost motion and hysteresis");
      report.plots.push_back(write_plot(*fig, out, "hysteresis.png", 800));
      page.image("hysteresis.png", "Torque against twist with the fitted stiffness");
    }
  }

  // Torsional stiffness, locked output.
  if (const json* torsional = torsional_section(run.results)) {
    page.heading("Torsional stiffness (locked output)");
    HtmlTable t = torsional_table(false);
    add_torsional_rows(t, run, std::nullopt);
    add_table(page, t);
    if (auto fig = torsional_loop_figure(*torsional)) {
      report.plots.push_back(write_plot(*fig, out, "torsional.png", 800));
      page.image("torsional.png", "Twist against torque, the locked-output loop");
    }
    if (const auto reason = torsional->find("t_max_reason");
        reason != torsional->end() && reason->is_string()) {
      page.paragraph("T_max: " + reason->get<std::string>());
    }
    HtmlTable budget = torsional_budget_table();
    add_torsional_budget_rows(budget, run);
    add_table(page, budget);
  }

  // Endurance: the trend per output revolution.
  if (const json* endurance = endurance_section(run.results)) {
    page.heading("Endurance");
    const json* diagnosis = nullptr;
    if (const auto t = run.results.find("twin"); t != run.results.end() && t->is_object()) {
      if (const auto d = t->find("diagnosis"); d != t->end() && d->is_object()) diagnosis = &*d;
    }
    if (auto fig = endurance_trend_figure(*endurance, diagnosis)) {
      report.plots.push_back(write_plot(*fig, out, "endurance.png", 800));
      page.image("endurance.png",
                 "TE, mesh lines, brake temperature and twin residual per output "
                 "revolution");
    }
    add_table(page, endurance_trend_table(*endurance));
  }

  // The twin.
  HtmlTable twin = twin_table(false);
  add_twin_rows(twin, run, std::nullopt, false);
  std::optional<Figure> twin_fig;
  if (run.twin) twin_fig = twin_figure(*run.twin);
  if (!twin.rows.empty() || twin_fig) {
    page.heading("The twin beside the bench");
    add_table(page, twin);
    if (twin_fig) {
      report.plots.push_back(write_plot(*twin_fig, out, "twin.png", 800));
      page.image("twin.png", "Twin against measured TE and the residual");
    }
  }
  add_twin_diagnosis_section(page, run);

  HtmlTable acquisition = acquisition_table();
  add_acquisition_rows(acquisition, run);
  if (!acquisition.rows.empty()) {
    page.heading("Acquisition");
    page.table(acquisition);
  }

  // The run's own files, linked so that the data behind every table is one click away.
  HtmlTable files;
  files.caption = "Files of the run";
  files.header = {"file", "size [bytes]"};
  for (const char* name : {"results.json", "status.json", "config.yaml", "samples.wbs", "twin.csv",
                           "twin-calibrated.yaml"}) {
    std::error_code ec;
    const fs::path f = run_dir / name;
    if (!fs::is_regular_file(f, ec)) continue;
    const std::string href = fs::absolute(f).lexically_relative(fs::absolute(out)).generic_string();
    files.rows.push_back({{name, href, false}, {std::to_string(fs::file_size(f, ec)), {}, false}});
  }
  if (!files.rows.empty()) {
    page.heading("Data");
    page.table(files);
  }

  if (!run.notes.empty()) {
    page.heading("Notes");
    page.list(run.notes);
  }
  report.notes = run.notes;
  report.html = out / "report.html";
  storage::write_file_atomically(report.html, page.str());
  return report;
}

std::vector<HtmlTable> session_tables(const std::vector<SessionRun>& runs,
                                      const fs::path& link_base) {
  HtmlTable overview = runs_table();
  HtmlTable st = static_te_table(true), lm = static_lost_motion_table(true),
            shift = load_shift_table(true), dyn = dynamic_te_table(true),
            stiff = stiffness_table(true), torsional = torsional_table(true),
            twin = twin_table(true);
  overview.caption = "Runs";
  twin.caption = "The twin: residual RMS";
  for (const auto& r : runs) {
    const RunFolder run = read_run_folder(r.run_dir, false);
    HtmlCell cell{run.run_id(), {}, false};
    if (!link_base.empty()) {
      const fs::path html = r.report_html.empty() ? r.run_dir / "report.html" : r.report_html;
      cell.href = fs::absolute(html).lexically_relative(fs::absolute(link_base)).generic_string();
    }
    HtmlCell plain{run.run_id(), {}, false};
    add_run_row(overview, run, cell);
    add_static_te_rows(st, run, plain);
    add_static_lost_motion_rows(lm, run, plain);
    add_load_shift_rows(shift, run, plain);
    add_dynamic_te_rows(dyn, run, plain);
    add_stiffness_rows(stiff, run, plain);
    add_torsional_rows(torsional, run, plain);
    add_twin_rows(twin, run, plain, true);
  }
  std::vector<HtmlTable> out;
  for (auto* t : {&overview, &st, &lm, &shift, &dyn, &stiff, &torsional, &twin}) {
    if (!t->rows.empty()) out.push_back(std::move(*t));
  }
  return out;
}

fs::path write_session_report(const fs::path& dir, const std::vector<fs::path>& run_dirs) {
  std::vector<SessionRun> runs;
  for (const auto& d : run_dirs) runs.push_back({d, {}});
  return write_session_report(dir, runs);
}

fs::path write_session_report(const fs::path& dir, const std::vector<SessionRun>& runs) {
  fs::create_directories(dir);
  HtmlPage page("Bench session: " + std::to_string(runs.size()) + " run" +
                (runs.size() == 1 ? "" : "s"));
  for (const auto& t : session_tables(runs, dir)) page.table(t);
  const fs::path index = dir / "index.html";
  storage::write_file_atomically(index, page.str());
  return index;
}

std::string tables_as_text(const std::vector<HtmlTable>& tables) {
  std::string out;
  for (const auto& t : tables) {
    std::vector<std::vector<std::string>> rows;
    rows.push_back(t.header);
    for (const auto& r : t.rows) {
      std::vector<std::string> cells;
      for (const auto& c : r) cells.push_back(c.text);
      rows.push_back(std::move(cells));
    }
    std::vector<std::size_t> width;
    for (const auto& r : rows) {
      if (width.size() < r.size()) width.resize(r.size(), 0);
      for (std::size_t i = 0; i < r.size(); ++i) {
        // Count code points, not bytes, so that "–" does not widen a column.
        std::size_t n = 0;
        for (const unsigned char ch : r[i]) n += (ch & 0xC0) != 0x80;
        width[i] = std::max(width[i], n);
      }
    }
    out += (t.caption.empty() ? std::string("Table") : t.caption) + "\n";
    for (const auto& r : rows) {
      std::string line = " ";
      for (std::size_t i = 0; i < r.size(); ++i) {
        std::size_t n = 0;
        for (const unsigned char ch : r[i]) n += (ch & 0xC0) != 0x80;
        line += " " + r[i] + std::string(width[i] - n, ' ') + " ";
      }
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out += line + "\n";
    }
    out += "\n";
  }
  return out;
}

}  // namespace wavebench::report
