// `wavebench report RUN_DIR [RUN_DIR...] [--out DIR]`: report.html and PNG plots of each run,
// and with more than one run an index.html gathering them; the summary tables on stdout.
//
// Without --out each report goes into its run folder and the index into the runs' common
// parent; with --out, one run's report goes into DIR, several go into DIR/<run folder>/ with
// the index in DIR. A folder of run folders (a run store root) stands for all its runs.
// Every RUN_DIR is checked before anything is written: a bad one exits 2.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "wavebench/report/run_report.hpp"

namespace wavebench::cli {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::vector<std::string> run_dirs;
  std::string out;
  bool quiet = false;
};

bool is_run_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) &&
         (fs::exists(dir / "status.json", ec) || fs::exists(dir / "results.json", ec) ||
          fs::exists(dir / "samples.wbs", ec));
}

// The run folders a command-line argument names: itself, or the run folders inside it.
std::vector<fs::path> expand(const fs::path& arg) {
  if (is_run_folder(arg)) return {arg};
  std::vector<fs::path> runs;
  std::error_code ec;
  if (fs::is_directory(arg, ec)) {
    for (const auto& entry : fs::directory_iterator(arg, ec)) {
      if (is_run_folder(entry.path())) runs.push_back(entry.path());
    }
  }
  std::sort(runs.begin(), runs.end());
  if (runs.empty()) runs.push_back(arg);  // read_run_folder names what is wrong with it
  return runs;
}

// The folder itself, without a trailing separator ("out/bench/run/" -> "out/bench/run").
fs::path normalised(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  return p.filename().empty() ? p.parent_path() : p;
}

// Where an index of runs from different places goes: their shared parent, else here.
fs::path common_parent(const std::vector<fs::path>& dirs) {
  const fs::path parent = normalised(dirs.front()).parent_path();
  for (const auto& d : dirs) {
    if (normalised(d).parent_path() != parent) return fs::current_path();
  }
  return parent;
}

int run_report(const ReportArgs& args) {
  std::vector<fs::path> runs;
  for (const auto& a : args.run_dirs) {
    for (auto& r : expand(a)) runs.push_back(std::move(r));
  }
  for (const auto& r : runs) {
    try {
      (void)report::read_run_folder(r, false);
    } catch (const std::invalid_argument& e) {
      std::cerr << "wavebench report: " << e.what() << "\n";
      return 2;
    }
  }
  const bool session = runs.size() > 1;
  std::vector<report::SessionRun> written;
  for (const auto& r : runs) {
    fs::path out_dir;
    if (!args.out.empty()) {
      out_dir = session ? fs::path(args.out) / normalised(r).filename() : fs::path(args.out);
    }
    const auto rep = report::write_run_report(r, out_dir);
    written.push_back({r, rep.html});
    if (!args.quiet) std::cout << "report: " << rep.html.string() << "\n";
  }
  const fs::path index_dir = !args.out.empty() ? fs::path(args.out) : common_parent(runs);
  if (!args.quiet) std::cout << "\n" << report::tables_as_text(report::session_tables(written));
  if (session) {
    const fs::path index = report::write_session_report(index_dir, written);
    std::cout << "session report: " << index.string() << "\n";
  } else {
    std::cout << "run report: " << written.front().report_html.string() << "\n";
  }
  return 0;
}

}  // namespace

void register_report_commands(CLI::App& app, ExitStatus& status) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report", "Write report.html and PNG plots of bench runs (and an index of several runs)");
  cmd->add_option("RUN_DIR", args->run_dirs,
                  "Run folder(s) (status.json, results.json, samples.wbs, twin.csv), or a "
                  "folder of run folders")
      ->required();
  cmd->add_option("--out", args->out, "Write the report(s) here instead of into the run folders");
  cmd->add_flag("--quiet", args->quiet, "Print only where the report is");
  cmd->callback([args, &status] { status.code = run_report(*args); });
}

}  // namespace wavebench::cli
