#include "wavebench/procedures/run_request_check.hpp"

#include <sys/statvfs.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "parsed_request.hpp"
#include "quoted_value.hpp"
#include "run_request_check_detail.hpp"

namespace wavebench::procedures {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::string bytes(std::uint64_t n) {
  std::ostringstream s;
  s.precision(3);
  if (n >= (1ull << 30)) {
    s << static_cast<double>(n) / (1ull << 30) << " GiB";
  } else if (n >= (1ull << 20)) {
    s << static_cast<double>(n) / (1ull << 20) << " MiB";
  } else {
    s << n << " bytes";
  }
  return s.str();
}

std::string duration(double s) {
  std::ostringstream o;
  o.precision(4);
  if (s >= 3600) {
    o << s / 3600 << " h";
  } else {
    o << s << " s";
  }
  return o.str();
}

// The smaller of the limits that are on (> 0); infinity when none is.
double tightest(std::initializer_list<double> limits) {
  double out = std::numeric_limits<double>::infinity();
  for (double l : limits) {
    if (l > 0) out = std::min(out, l);
  }
  return out;
}

void check_at_most(const std::vector<CommandedValue>& values, double limit_si,
                   const char* limit_name) {
  if (!std::isfinite(limit_si)) return;
  for (const auto& v : values) {
    if (std::abs(v.si()) > limit_si) {
      throw std::invalid_argument(v.key + ": got '" + number(v.given) + "', expected at most " +
                                  number(limit_si / v.per_unit) + " " + v.unit + " (" + limit_name +
                                  ")");
    }
  }
}

RunPlan plan_of(const AnyProcedure& procedure, const bench::BenchDescription& bench) {
  return std::visit([&](const auto& p) { return p.plan(bench); }, procedure);
}

}  // namespace

RunBudget run_budget(const std::filesystem::path& runs_root) {
  // The nearest ancestor that exists: the root itself is created with the first run.
  std::filesystem::path probe = runs_root.empty() ? "." : std::filesystem::absolute(runs_root);
  std::error_code ec;
  while (!std::filesystem::exists(probe, ec) && probe.has_parent_path() &&
         probe.parent_path() != probe) {
    probe = probe.parent_path();
  }
  struct statvfs fs {};
  if (::statvfs(probe.c_str(), &fs) != 0) {
    throw std::invalid_argument("runs folder " + runs_root.string() + ": cannot examine " +
                                probe.string() + " (" + std::strerror(errno) +
                                "), expected a folder on a writable file system");
  }
  RunBudget budget;
  budget.runs_root = runs_root;
  budget.free_disk_bytes = static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize;
  return budget;
}

void check_run_identity(const RunRequest& request) {
  const auto refuse = [](const char* key, const std::string& value, const char* expected) {
    throw std::invalid_argument(std::string(key) + ": got '" + quoted_value(value) +
                                "', expected " + expected);
  };
  if (!request.unit_serial.empty()) {
    const bool ok = request.unit_serial.size() <= 64 &&
                    request.unit_serial.find_first_not_of(
                        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._/-") ==
                        std::string::npos;
    if (!ok) refuse("unit_serial", request.unit_serial, "1 to 64 of A-Z a-z 0-9 . _ / -");
  }
  if (!request.operator_name.empty()) {
    bool ok = request.operator_name.size() <= 64;
    for (const unsigned char c : request.operator_name) {
      ok = ok && c >= 0x20 && c != 0x7f && c != '"' && c != '\\' && c != '<' && c != '>';
    }
    if (!ok) {
      refuse("operator", request.operator_name,
             "1 to 64 printable characters without quotes, backslashes or angle brackets");
    }
  }
}

ParsedRequest check_and_parse(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const RunBudget& budget,
                              RunEstimate* estimate) {
  check_run_identity(request);
  ParsedRequest parsed = parse_request(request);
  RunPlan plan = plan_of(parsed.procedure, bench);
  if (parsed.repeats > 1) {
    // Every repeat commands the same values and takes as long.
    plan.bench_time_s *= parsed.repeats;
    plan.duration_terms =
        std::to_string(parsed.repeats) + " repeats x (" + plan.duration_terms + ")";
  }
  check_at_most(plan.brake_torques_nm,
                tightest({bench.max_brake_torque_nm, bench.limits.max_brake_torque_nm}),
                "the bench's brake limit");
  check_at_most(plan.input_speeds_rad_s, tightest({bench.limits.max_input_speed_rad_s}),
                "the bench's input speed limit");
  if (!plan.refusal.empty()) throw std::invalid_argument(plan.refusal);

  const RunEstimate e = estimate_run(plan, bench, extra_channels, request.twin);
  if (!(e.bench_time_s <= budget.max_bench_time_s)) {
    throw std::invalid_argument(request.procedure + ": got " + plan.duration_terms +
                                " = an estimated " + duration(e.bench_time_s) +
                                " of bench time, expected at most " +
                                duration(budget.max_bench_time_s) + " (the run duration bound)");
  }
  if (e.disk_bytes() > budget.free_disk_bytes) {
    throw std::invalid_argument(
        request.procedure + ": got an estimated " + bytes(e.disk_bytes()) + " to write (" +
        std::to_string(e.samples) + " samples over " + duration(e.bench_time_s) +
        (request.twin ? ", the twin's trace" : "") + ", results and report), expected at most " +
        bytes(budget.free_disk_bytes) + " (free on the file system of the runs folder " +
        budget.runs_root.string() + ")");
  }
  if (estimate) *estimate = e;
  return parsed;
}

RunEstimate check_run_request(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const RunBudget& budget) {
  RunEstimate e;
  check_and_parse(request, bench, extra_channels, budget, &e);
  return e;
}

RunEstimate check_run_request(const RunRequest& request, const bench::BenchDescription& bench,
                              std::size_t extra_channels, const std::filesystem::path& runs_root) {
  return check_run_request(request, bench, extra_channels, run_budget(runs_root));
}

}  // namespace wavebench::procedures
