#pragma once
// The report of a bench run (issue #5): report.html and its PNG plots, written from what the
// run folder holds (see run_folder.hpp), and a session page that gathers several runs.
//
// Usage (e.g. at the end of procedures::execute_run, after results.json, status.json and twin.csv):
//   report::write_run_report(run_dir);                 // run_dir/report.html + *.png
//   report::write_session_report(out, {dir_a, dir_b});  // out/index.html linking each report
//
// A section the results do not hold is left out of the page, never an error. The page is
// self-contained (inline style, PNGs linked by relative path) and every text from the run is
// escaped.

#include <filesystem>
#include <string>
#include <vector>

#include "wavebench/report/html_page.hpp"
#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

struct RunReport {
  std::filesystem::path html;
  std::vector<std::filesystem::path> plots;
  std::vector<std::string> notes;  // what was missing (also listed on the page)
};

// Writes report.html and the plots into `out_dir` (the run folder when empty). Throws
// std::invalid_argument when run_dir is not a run folder, std::runtime_error or
// std::system_error naming the path when a file cannot be written. report.html is replaced
// atomically, after its plots.
RunReport write_run_report(const std::filesystem::path& run_dir,
                           const std::filesystem::path& out_dir = {});

struct SessionRun {
  std::filesystem::path run_dir;
  std::filesystem::path report_html;  // linked from the index; run_dir/report.html when empty
};

// index.html in `dir` with the combined summary tables, each run linking its report by a
// relative path. Returns the path of index.html. Throws as write_run_report.
std::filesystem::path write_session_report(const std::filesystem::path& dir,
                                           const std::vector<std::filesystem::path>& run_dirs);
std::filesystem::path write_session_report(const std::filesystem::path& dir,
                                           const std::vector<SessionRun>& runs);

// The summary tables of a session (runs; static TE per direction and load; dynamic TE;
// lost motion and stiffness; twin residual), as the index shows them. Tables without rows
// are left out. `link_base` makes the run ids links relative to it when not empty.
std::vector<HtmlTable> session_tables(const std::vector<SessionRun>& runs,
                                      const std::filesystem::path& link_base = {});
// The same tables as aligned plain text for a terminal.
std::string tables_as_text(const std::vector<HtmlTable>& tables);

}  // namespace wavebench::report
