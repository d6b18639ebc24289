// HDF5 through the HDF5 C library: /samples/<column> as chunked, extendible 1-D datasets, each
// page appended as it is read; a "unit" attribute on every channel; results_json, run_json and
// /results (numbers, numeric lists, strings; objects as groups) at the root.
#include <hdf5.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "export_columns.hpp"
#include "export_writers.hpp"

namespace wavebench::exports::detail {

namespace {

using nlohmann::json;

// One HDF5 identifier, closed with its own H5*close when it goes.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what);
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  hid_t get() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// The innermost message of libhdf5's error stack (for a failed write, the system's: "file
// write failed: ... errno = 28, error message = 'No space left on device'").
std::string hdf5_error_text() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* out) -> herr_t {
        if (n == 0 && e->desc) *static_cast<std::string*>(out) = e->desc;
        return 0;
      },
      &text);
  // A failed system call's description is long (time, buffer address, sizes): its reason is
  // the part that matters to the user.
  if (const auto at = text.find("error message = '"); at != std::string::npos) {
    const auto begin = at + 17;
    const auto end = text.find('\'', begin);
    const auto errno_at = text.find("errno = ");
    std::string why = text.substr(begin, end == std::string::npos ? end : end - begin);
    if (errno_at != std::string::npos) {
      why += " (errno " + text.substr(errno_at + 8, text.find(',', errno_at) - errno_at - 8) + ")";
    }
    return why;
  }
  return text;
}

[[noreturn]] void fail(const std::string& what) {
  const std::string why = hdf5_error_text();
  throw std::runtime_error("HDF5: " + what + " failed" + (why.empty() ? "" : ": " + why));
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Handle::Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
  if (id_ < 0) fail(what);
}

// The file being written. Closed by close() when complete; when it is given up (an exception,
// a full disk) its descriptor is first pointed at a scratch memory file so that the close's
// flush cannot fail: libhdf5 1.10 keeps the id of a file whose close failed, half torn down,
// and H5close at exit then crashes on it (issue #22: SIGSEGV at exit or SIGTERM). The bytes
// written to the memory file are dropped; the temporary file on disk is removed by the caller.
class Hdf5File {
 public:
  explicit Hdf5File(const std::filesystem::path& file) {
    Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
    // Closing the file closes whatever is still open in it: nothing outlives an error.
    check(H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG), "close degree");
    id_ = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get());
    if (id_ < 0) fail("create " + file.string());
  }
  ~Hdf5File() {
    if (id_ < 0) return;
    void* handle = nullptr;
    if (H5Fget_vfd_handle(id_, H5P_DEFAULT, &handle) >= 0 && handle) {
      const int discard = ::memfd_create("wavebench-hdf5-discard", MFD_CLOEXEC);
      if (discard >= 0) {
        ::dup2(discard, *static_cast<int*>(handle));
        ::close(discard);
      }
    }
    H5Fclose(id_);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  hid_t get() const { return id_; }

  void close() {
    const hid_t id = id_;
    id_ = -1;
    if (H5Fclose(id) < 0) {
      id_ = id;  // still open in the library: given up as above
      fail("close");
    }
  }

 private:
  hid_t id_ = -1;
};

Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  check(H5Tset_size(t.get(), H5T_VARIABLE), "string size");
  check(H5Tset_cset(t.get(), H5T_CSET_UTF8), "string character set");
  return t;
}

void string_attribute(hid_t object, const char* name, const std::string& value) {
  const auto type = string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle attr(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("attribute ") + name);
  const char* text = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &text), std::string("attribute ") + name);
}

void string_dataset(hid_t where, const std::string& name, const std::string& value) {
  const auto type = string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "scalar space");
  Handle ds(H5Dcreate2(where, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                       H5P_DEFAULT),
            H5Dclose, "dataset " + name);
  const char* text = value.c_str();
  check(H5Dwrite(ds.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text), "write " + name);
}

void double_dataset(hid_t where, const std::string& name, const std::vector<double>& values,
                    bool scalar) {
  const hsize_t dims[1] = {values.size()};
  Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr), H5Sclose,
               "space of " + name);
  Handle ds(H5Dcreate2(where, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                       H5P_DEFAULT),
            H5Dclose, "dataset " + name);
  if (!values.empty()) {
    check(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "write " + name);
  }
}

double number(const json& v) {
  return v.is_boolean() ? (v.get<bool>() ? 1.0 : 0.0) : v.get<double>();
}

// Numbers and booleans as scalar doubles, numeric lists as vectors, strings as strings,
// objects as groups; the rest (null, lists of objects) only in results_json.
void results_into(hid_t group, const json& j, int depth) {
  for (const auto& [key, value] : j.items()) {
    const auto name = field_name(key);
    if (name.empty() || H5Lexists(group, name.c_str(), H5P_DEFAULT) > 0) continue;
    if (value.is_number() || value.is_boolean()) {
      double_dataset(group, name, {number(value)}, true);
    } else if (value.is_string()) {
      string_dataset(group, name, value.get<std::string>());
    } else if (value.is_array() && !value.empty() &&
               std::all_of(value.begin(), value.end(),
                           [](const json& x) { return x.is_number() || x.is_boolean(); })) {
      std::vector<double> v;
      for (const auto& x : value) v.push_back(number(x));
      double_dataset(group, name, v, false);
    } else if (value.is_object() && depth < 8) {
      Handle sub(H5Gcreate2(group, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "group " + name);
      results_into(sub.get(), value, depth + 1);
    }
  }
}

struct ColumnDataset {
  const ExportColumn* column;
  hid_t memory_type;
  Handle dataset;
};

constexpr hsize_t kChunk = 16384;

// The file's contents; its objects are closed when this returns.
PageWalk write_contents(hid_t h5, const ExportInput& input) {
  string_attribute(h5, "run_id", input.run_id);
  string_attribute(h5, "written_by", "wavebench export");
  // "true": the run was still running, the file holds only the samples logged so far.
  string_attribute(h5, "partial", input.partial ? "true" : "false");
  Handle samples(H5Gcreate2(h5, "samples", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "group samples");
  const auto columns = export_columns(extra_channels_of(input));
  std::vector<ColumnDataset> sets;
  for (const auto& c : columns) {
    hid_t file_type = H5T_IEEE_F64LE, memory_type = H5T_NATIVE_DOUBLE;
    switch (c.type) {
      case ColumnType::kUint32:
        file_type = H5T_STD_U32LE;
        memory_type = H5T_NATIVE_UINT32;
        break;
      case ColumnType::kUint64:
        file_type = H5T_STD_U64LE;
        memory_type = H5T_NATIVE_UINT64;
        break;
      case ColumnType::kInt64:
        file_type = H5T_STD_I64LE;
        memory_type = H5T_NATIVE_INT64;
        break;
      case ColumnType::kDouble:
        break;
    }
    const hsize_t dims[1] = {0}, max_dims[1] = {H5S_UNLIMITED}, chunk[1] = {kChunk};
    Handle space(H5Screate_simple(1, dims, max_dims), H5Sclose, "space of " + c.name);
    Handle create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "properties of " + c.name);
    check(H5Pset_chunk(create.get(), 1, chunk), "chunks of " + c.name);
    Handle ds(H5Dcreate2(samples.get(), c.name.c_str(), file_type, space.get(), H5P_DEFAULT,
                         create.get(), H5P_DEFAULT),
              H5Dclose, "dataset " + c.name);
    if (!c.unit.empty()) string_attribute(ds.get(), "unit", c.unit);
    string_attribute(ds.get(), "description", c.description);
    sets.push_back({&c, memory_type, std::move(ds)});
  }

  std::vector<double> reals;
  std::vector<std::int64_t> integers;
  std::vector<std::uint64_t> unsigned64;
  std::vector<std::uint32_t> unsigned32;
  hsize_t written = 0;
  auto walk = walk_pages(input, [&](const storage::SampleLogPage& page) {
    const hsize_t n = page.samples.size();
    const hsize_t new_size[1] = {written + n}, start[1] = {written}, count[1] = {n};
    for (auto& set : sets) {
      const void* data = nullptr;
      const auto& c = *set.column;
      switch (c.type) {
        case ColumnType::kDouble:
          reals.clear();
          for (const auto& s : page.samples) reals.push_back(c.real(s));
          data = reals.data();
          break;
        case ColumnType::kInt64:
          integers.clear();
          for (const auto& s : page.samples) integers.push_back(c.integer(s));
          data = integers.data();
          break;
        case ColumnType::kUint64:
          unsigned64.clear();
          for (const auto& s : page.samples)
            unsigned64.push_back(static_cast<std::uint64_t>(c.integer(s)));
          data = unsigned64.data();
          break;
        case ColumnType::kUint32:
          unsigned32.clear();
          for (const auto& s : page.samples)
            unsigned32.push_back(static_cast<std::uint32_t>(c.integer(s)));
          data = unsigned32.data();
          break;
      }
      check(H5Dset_extent(set.dataset.get(), new_size), "extend " + c.name);
      Handle file_space(H5Dget_space(set.dataset.get()), H5Sclose, "space of " + c.name);
      check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
            "select in " + c.name);
      Handle memory_space(H5Screate_simple(1, count, nullptr), H5Sclose, "page space");
      check(H5Dwrite(set.dataset.get(), set.memory_type, memory_space.get(), file_space.get(),
                     H5P_DEFAULT, data),
            "write " + c.name);
    }
    written += n;
  });

  const json results = input.results.is_null() ? json::object() : input.results;
  string_dataset(h5, "results_json", json_text(results));
  string_dataset(h5, "run_json", json_text(input.run));
  Handle group(H5Gcreate2(h5, "results", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
               "group results");
  results_into(group.get(), results, 0);
  sets.clear();
  // Everything reaches the file while its objects are open: a failure here is an exception
  // and the file is given up, not a close that fails half way.
  check(H5Fflush(h5, H5F_SCOPE_GLOBAL), "flush");
  return walk;
}

}  // namespace

PageWalk write_hdf5_file(const ExportInput& input, const std::filesystem::path& file) {
  // No library teardown at exit: a file whose close failed (the scratch memory file full too)
  // stays half torn down in libhdf5 1.10, and H5close at exit or SIGTERM would crash on it.
  // Every file is closed here, on every path; nothing is left for the teardown to flush.
  static const bool no_teardown_at_exit = H5dont_atexit() >= 0;
  (void)no_teardown_at_exit;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions, not stderr noise
  Hdf5File h5(file);
  const auto walk = write_contents(h5.get(), input);
  h5.close();
  return walk;
}

}  // namespace wavebench::exports::detail
