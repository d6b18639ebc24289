// MATLAB MAT 5 through libmatio. Each column is one variable, written whole (MAT 5 states a
// variable's size before its data): columns are collected from the pages as many at a time as
// fit kColumnBudgetBytes (all of them for a short log, one per pass for a very long one), never
// the log's records.
#include <matio.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "export_columns.hpp"
#include "export_writers.hpp"

namespace wavebench::exports::detail {

namespace {

using nlohmann::json;

struct MatFileCloser {
  void operator()(mat_t* m) const { Mat_Close(m); }
};
struct MatVarFree {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using MatFile = std::unique_ptr<mat_t, MatFileCloser>;
using MatVar = std::unique_ptr<matvar_t, MatVarFree>;

MatVar checked(matvar_t* v, const std::string& name) {
  if (!v) throw std::runtime_error("matio: cannot create variable " + name);
  return MatVar(v);
}

// The variable points at the caller's buffer (not copied, not freed): write it before the
// buffer goes.
MatVar column_var(const char* name, matio_classes cls, matio_types type, std::size_t n,
                  const void* data) {
  std::size_t dims[2] = {n, 1};
  return checked(
      Mat_VarCreate(name, cls, type, 2, dims, const_cast<void*>(data), MAT_F_DONT_COPY_DATA),
      name ? name : "(field)");
}

MatVar char_var(const char* name, const std::string& text) {
  // ASCII only (results_json is dumped with \u escapes): MAT 5 char data as 8-bit.
  std::string ascii = text;
  for (auto& c : ascii) {
    if (static_cast<unsigned char>(c) >= 0x80) c = '?';
  }
  std::size_t dims[2] = {1, ascii.size()};
  return checked(Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT8, 2, dims, ascii.data(), 0),
                 name ? name : "(field)");
}

MatVar double_var(const char* name, const std::vector<double>& values, bool row = true) {
  std::size_t dims[2] = {row ? 1 : values.size(), row ? values.size() : 1};
  return checked(Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                               const_cast<double*>(values.data()), 0),
                 name ? name : "(field)");
}

void write(mat_t* mat, MatVar var, const std::string& name, std::size_t& written) {
  if (Mat_VarWrite(mat, var.get(), MAT_COMPRESSION_NONE) != 0) {
    throw std::runtime_error("matio: cannot write variable " + name);
  }
  ++written;
}

// libmatio writes through stdio and does not report a write that failed (a full disk: it
// returns success for a file cut short). So the file is checked as MAT 5 lays it out: a
// 128-byte header, then one tagged element per variable (u32 type, u32 byte count, the
// bytes), ending exactly at the end of the file.
void check_mat5_layout(const std::filesystem::path& file, std::size_t variables) {
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  const auto cut = [&](const std::string& why) {
    throw std::runtime_error("matio: the file was not written whole (" + why +
                             "; is the disk full?)");
  };
  if (!in || ec || size < 128) cut("no header");
  std::uint64_t at = 128;
  for (std::size_t i = 0; i < variables; ++i) {
    unsigned char tag[8];
    in.seekg(static_cast<std::streamoff>(at));
    if (at + 8 > size || !in.read(reinterpret_cast<char*>(tag), 8)) {
      cut("variable " + std::to_string(i + 1) + " of " + std::to_string(variables) + " missing");
    }
    std::uint32_t bytes = 0;
    std::memcpy(&bytes, tag + 4, 4);  // written in this machine's order, as the header says
    at += 8 + std::uint64_t{bytes};
    if (at > size) cut("variable " + std::to_string(i + 1) + " cut short");
  }
  if (at != size) cut(std::to_string(size - at) + " bytes after the last variable");
}

bool numeric_list(const json& j) {
  if (!j.is_array() || j.empty()) return false;
  for (const auto& v : j) {
    if (!v.is_number() && !v.is_boolean()) return false;
  }
  return true;
}

// A JSON value as a MATLAB value: objects as structs, numbers and booleans as doubles, numeric
// lists as row vectors, strings as char; null, mixed lists and lists of objects as [] (they are
// in results_json). Depth-limited: results are a few levels deep.
MatVar to_mat(const char* name, const json& j, int depth) {
  if (j.is_number() || j.is_boolean()) {
    return double_var(name, {j.is_boolean() ? (j.get<bool>() ? 1.0 : 0.0) : j.get<double>()});
  }
  if (j.is_string()) return char_var(name, j.get<std::string>());
  if (numeric_list(j)) {
    std::vector<double> v;
    for (const auto& x : j)
      v.push_back(x.is_boolean() ? (x.get<bool>() ? 1.0 : 0.0) : x.get<double>());
    return double_var(name, v);
  }
  if (j.is_object() && depth < 8) {
    std::vector<std::string> names;
    std::vector<const json*> values;
    std::set<std::string> seen;
    for (const auto& [key, value] : j.items()) {
      const auto field = field_name(key);
      if (field.empty() || !seen.insert(field).second) continue;
      names.push_back(field);
      values.push_back(&value);
    }
    std::vector<const char*> fields;
    for (const auto& n : names) fields.push_back(n.c_str());
    std::size_t dims[2] = {1, 1};
    auto s = checked(
        Mat_VarCreateStruct(name, 2, dims, fields.data(), static_cast<unsigned>(fields.size())),
        name ? name : "(struct)");
    for (std::size_t i = 0; i < names.size(); ++i) {
      // The struct owns the field from here; what comes back is the field it held before
      // (none: the struct is new).
      Mat_VarSetStructFieldByName(s.get(), names[i].c_str(), 0,
                                  to_mat(nullptr, *values[i], depth + 1).release());
    }
    return s;
  }
  return double_var(name, {});
}

// One column's values as its type wants them.
struct ColumnValues {
  std::vector<double> reals;
  std::vector<std::uint32_t> u32;
  std::vector<std::uint64_t> u64;
  std::vector<std::int64_t> i64;

  void add(const ExportColumn& c, const storage::SyncSample& s) {
    switch (c.type) {
      case ColumnType::kDouble:
        reals.push_back(c.real(s));
        break;
      case ColumnType::kUint32:
        u32.push_back(static_cast<std::uint32_t>(c.integer(s)));
        break;
      case ColumnType::kUint64:
        u64.push_back(static_cast<std::uint64_t>(c.integer(s)));
        break;
      case ColumnType::kInt64:
        i64.push_back(c.integer(s));
        break;
    }
  }
  MatVar var(const ExportColumn& c) const {
    const char* name = c.name.c_str();
    switch (c.type) {
      case ColumnType::kDouble:
        return column_var(name, MAT_C_DOUBLE, MAT_T_DOUBLE, reals.size(), reals.data());
      case ColumnType::kUint32:
        return column_var(name, MAT_C_UINT32, MAT_T_UINT32, u32.size(), u32.data());
      case ColumnType::kUint64:
        return column_var(name, MAT_C_UINT64, MAT_T_UINT64, u64.size(), u64.data());
      case ColumnType::kInt64:
        return column_var(name, MAT_C_INT64, MAT_T_INT64, i64.size(), i64.data());
    }
    throw std::logic_error("column type");
  }
};

// Columns collected together in one pass over the pages, as many as fit this.
constexpr std::uint64_t kColumnBudgetBytes = std::uint64_t{64} << 20;

}  // namespace

PageWalk write_mat_file(const ExportInput& input, const std::filesystem::path& file) {
  const std::string header = "MATLAB 5.0 MAT-file, wavebench export of run " + input.run_id;
  MatFile mat(Mat_CreateVer(file.c_str(), header.c_str(), MAT_FT_MAT5));
  if (!mat) throw std::runtime_error("matio: cannot create the file");
  const auto first = input.pages(0, 1);
  const auto columns = export_columns(first.header.extra_channels);
  // A short log goes in one pass; a long one in as few as keep each pass's columns within the
  // budget (one column per pass at worst).
  const std::uint64_t bytes_per_column = std::max<std::uint64_t>(8 * first.total_records, 1);
  const std::size_t per_pass =
      static_cast<std::size_t>(std::max<std::uint64_t>(1, kColumnBudgetBytes / bytes_per_column));
  PageWalk walk;
  std::size_t variables = 0;
  std::vector<std::string> unit_names;
  std::vector<std::string> unit_values;
  for (std::size_t begin = 0; begin < columns.size(); begin += per_pass) {
    const std::size_t end = std::min(columns.size(), begin + per_pass);
    std::vector<ColumnValues> values(end - begin);
    walk = walk_pages(input, [&](const storage::SampleLogPage& page) {
      for (std::size_t i = begin; i < end; ++i) {
        for (const auto& s : page.samples) values[i - begin].add(columns[i], s);
      }
    });
    for (std::size_t i = begin; i < end; ++i) {
      write(mat.get(), values[i - begin].var(columns[i]), columns[i].name, variables);
      values[i - begin] = ColumnValues();  // written: its memory goes before the next
      if (!columns[i].unit.empty()) {
        unit_names.push_back(columns[i].name);
        unit_values.push_back(columns[i].unit);
      }
    }
  }
  json units = json::object();
  for (std::size_t i = 0; i < unit_names.size(); ++i) units[unit_names[i]] = unit_values[i];
  write(mat.get(), to_mat("units", units, 0), "units", variables);
  const json results = input.results.is_null() ? json::object() : input.results;
  // ensure_ascii: MAT 5 char data here is 8-bit; \u escapes keep the text exact.
  write(mat.get(), char_var("results_json", json_text(results, true)), "results_json", variables);
  write(mat.get(), char_var("run_json", json_text(input.run, true)), "run_json", variables);
  write(mat.get(), to_mat("results", results, 0), "results", variables);
  write(mat.get(), char_var("run_id", input.run_id), "run_id", variables);
  // 1: the run was still running, the file holds only the samples logged so far.
  write(mat.get(), double_var("partial", {input.partial ? 1.0 : 0.0}), "partial", variables);
  if (Mat_Close(mat.release()) != 0) throw std::runtime_error("matio: cannot close the file");
  check_mat5_layout(file, variables);
  return walk;
}

}  // namespace wavebench::exports::detail
