#include "wavebench/report/twin_csv_envelope.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <string_view>

#include "wavebench/analysis/min_max_envelope.hpp"

namespace wavebench::report {
namespace {

namespace fs = std::filesystem;

enum Column { kT, kMeasured, kPredicted, kResidual, kColumns };

// Which of the four columns each cell of a row is (kColumns: none of them).
struct Layout {
  std::vector<int> cell_column;
  std::array<bool, kColumns> present{};
};

Layout layout_of(std::string_view header) {
  Layout l;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = header.find(',', start);
    const std::string_view name = header.substr(start, comma - start);
    int c = kColumns;
    if (name == "t") c = kT;
    if (name == "measured_te_arcsec") c = kMeasured;
    if (name == "predicted_te_arcsec") c = kPredicted;
    if (name == "residual_arcsec") c = kResidual;
    if (c != kColumns) l.present[static_cast<std::size_t>(c)] = true;
    l.cell_column.push_back(c);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return l;
}

// One row's values (NaN where the column is absent); false when the row is malformed: a cell
// count unlike the header's or a cell of the four that is not wholly a number. Hand-split with
// from_chars because a one-hour run's twin.csv has millions of rows and a stream per row would
// dominate the report's time.
bool parse_row(std::string_view line, const Layout& layout, std::array<double, kColumns>& out) {
  out.fill(std::numeric_limits<double>::quiet_NaN());
  std::size_t start = 0, cell = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view text = line.substr(start, comma - start);
    if (cell >= layout.cell_column.size()) return false;
    const int c = layout.cell_column[cell++];
    if (c != kColumns) {
      double v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return false;
      out[static_cast<std::size_t>(c)] = v;
    }
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cell == layout.cell_column.size();
}

std::string_view trimmed(const std::string& line) {
  std::string_view v(line);
  if (!v.empty() && v.back() == '\r') v.remove_suffix(1);
  return v;
}

// The time of the last usable row, from the file's tail (the file is written in time order).
std::optional<double> last_row_time(const fs::path& path, const Layout& layout) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::int64_t>(in.tellg());
  std::array<double, kColumns> row{};
  // Widen the tail until it holds a usable row (one row is well under 4 KiB).
  for (std::int64_t tail = 4096;; tail *= 4) {
    const std::int64_t start = std::max<std::int64_t>(0, size - tail);
    in.clear();
    in.seekg(start);
    std::string text(static_cast<std::size_t>(size - start), '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    std::size_t end = text.size();
    while (end > 0) {
      const std::size_t nl = text.rfind('\n', end - 1);
      if (nl == std::string::npos && start > 0) break;  // a partial line: widen the tail
      const std::size_t begin = nl == std::string::npos ? 0 : nl + 1;
      std::string_view line(text.data() + begin, end - begin);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (!line.empty() && parse_row(line, layout, row)) return row[kT];
      if (nl == std::string::npos) return std::nullopt;
      end = nl;
    }
    if (start == 0) return std::nullopt;
  }
}

}  // namespace

std::optional<TwinTrace> read_twin_csv_envelope(const fs::path& path, std::size_t columns,
                                                std::vector<std::string>& notes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line)) {
    notes.push_back("twin.csv is empty; the twin plot is left out");
    return std::nullopt;
  }
  const Layout layout = layout_of(trimmed(line));
  const auto no_rows = [&] {
    notes.push_back("twin.csv has no usable rows (needs column t); the twin plot is left out");
    return std::nullopt;
  };
  if (!layout.present[kT]) return no_rows();
  const bool derive_residual =
      !layout.present[kResidual] && layout.present[kMeasured] && layout.present[kPredicted];

  std::size_t bad_rows = 0, rows = 0;
  std::array<double, kColumns> row{};
  std::optional<analysis::MinMaxEnvelope> envelope;
  while (std::getline(in, line)) {
    const std::string_view text = trimmed(line);
    if (text.empty()) continue;
    if (!parse_row(text, layout, row)) {
      ++bad_rows;
      continue;
    }
    if (!envelope) {
      const double t1 = last_row_time(path, layout).value_or(row[kT]);
      envelope.emplace(row[kT], std::max(row[kT], t1), columns, 3);
    }
    if (derive_residual) row[kResidual] = row[kMeasured] - row[kPredicted];
    ++rows;
    envelope->add(row[kT], std::span<const double>(&row[kMeasured], 3));
  }
  if (bad_rows > 0) {
    notes.push_back("twin.csv: " + std::to_string(bad_rows) + " malformed rows skipped");
  }
  if (!envelope) return no_rows();
  if (const auto outside = envelope->samples_outside_range(); outside > 0) {
    notes.push_back("twin.csv: " + std::to_string(outside) +
                    " rows out of time order left out of the plot");
  }
  auto drawn = envelope->result();
  TwinTrace trace;
  trace.rows = rows;
  trace.t = std::move(drawn.t);
  if (layout.present[kMeasured]) trace.measured_te_arcsec = std::move(drawn.series[0]);
  if (layout.present[kPredicted]) trace.predicted_te_arcsec = std::move(drawn.series[1]);
  if (layout.present[kResidual] || derive_residual) {
    trace.residual_arcsec = std::move(drawn.series[2]);
  }
  return trace;
}

}  // namespace wavebench::report
