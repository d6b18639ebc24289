// The export path (issue #22): every format x sample counts x channel values x results shapes,
// the file cut off at a size the input chooses (RLIMIT_FSIZE: a full disk). An export either
// succeeds with the whole file or throws std::runtime_error leaving nothing under the real
// name and no temporary; anything else (a crash, libhdf5 at exit, a leftover) is a finding.
//
// Input bytes: [format][cap: 3 bytes][samples: 2 bytes][extra channels][results bytes...]
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/exports/export_format.hpp"
#include "wavebench/exports/run_export.hpp"
#include "wavebench/exports/sample_export.hpp"

namespace {

namespace fs = std::filesystem;
using namespace wavebench;

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return at_ < size_ ? data_[at_++] : 0; }
  double real() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits = (bits << 8) | next();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    return v;  // any double: NaN, infinities, subnormals
  }
  std::string rest() {
    std::string s(reinterpret_cast<const char*>(data_ + at_), size_ - std::min(at_, size_));
    at_ = size_;
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

const fs::path& work_dir() {
  static const fs::path dir = [] {
    auto d = fs::temp_directory_path() / ("wavebench-fuzz-exports-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::signal(SIGXFSZ, SIG_IGN);
    return d;
  }();
  return dir;
}

struct FileSizeCap {
  explicit FileSizeCap(rlim_t cap) {
    ::getrlimit(RLIMIT_FSIZE, &saved);
    rlimit l = saved;
    l.rlim_cur = cap;
    ::setrlimit(RLIMIT_FSIZE, &l);
  }
  ~FileSizeCap() { ::setrlimit(RLIMIT_FSIZE, &saved); }
  rlimit saved{};
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  constexpr exports::ExportFormat kFormats[] = {
      exports::ExportFormat::kMat, exports::ExportFormat::kHdf5, exports::ExportFormat::kCsv,
      exports::ExportFormat::kJson};
  const auto format = kFormats[in.next() % 4];
  rlim_t cap = (rlim_t{in.next()} << 16) | (rlim_t{in.next()} << 8) | in.next();
  if (cap == 0xFFFFFF) cap = RLIM_INFINITY;
  const std::uint64_t samples = ((std::uint64_t{in.next()} << 8) | in.next()) % 20000;
  const std::size_t extras = in.next() % 4;
  const double value = in.real();
  const bool running = in.next() & 1;
  const std::string results_text = in.rest();

  exports::ExportInput input;
  input.run_id = "20260101T000000.000000Z";
  input.run = {{"id", input.run_id}, {"status", running ? "running" : "complete"}};
  input.results = nlohmann::json::parse(results_text, nullptr, false);
  if (input.results.is_discarded()) input.results = {{"text", results_text}};
  input.page_records = 1 + samples / 3;
  input.sample_json = [](const storage::SyncSample& s, std::span<const storage::ChannelInfo>) {
    return nlohmann::json{{"index", s.index}, {"torque", s.torque_nm}};
  };
  input.pages = [samples, extras, value](std::uint64_t from, std::size_t count) {
    storage::SampleLogPage page;
    for (std::size_t i = 0; i < extras; ++i) {
      page.header.extra_channels.push_back({"ch" + std::to_string(i), "K"});
    }
    page.from = from;
    page.total_records = samples;
    for (std::uint64_t i = from; i < samples && i < from + count; ++i) {
      storage::SyncSample s;
      s.index = i;
      s.flags = static_cast<std::uint32_t>(i);
      s.torque_nm = value;
      s.theta_in_rad = value * static_cast<double>(i);
      for (std::size_t e = 0; e < extras; ++e) s.extra[e] = value;
      s.extra_valid = static_cast<std::uint32_t>(i);
      page.samples.push_back(s);
    }
    return page;
  };

  const fs::path dir = work_dir() / "out";
  bool ok = false;
  {
    FileSizeCap disk(cap);
    try {
      exports::export_run(input, format, dir, running && (cap & 1));
      ok = true;
    } catch (const std::runtime_error&) {
    } catch (const std::system_error&) {
    }
  }
  // A failed first export leaves no folder; a good one leaves exactly its files.
  std::error_code ec;
  if (!ok && fs::exists(dir, ec)) std::abort();
  if (ok) {
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const auto name = e.path().filename().string();
      if (name[0] == '.' && name != ".wavebench-export") std::abort();  // a leftover temporary
    }
    if (!fs::exists(dir / exports::samples_file_name(format), ec)) std::abort();
  }
  fs::remove_all(dir, ec);
  return 0;
}
