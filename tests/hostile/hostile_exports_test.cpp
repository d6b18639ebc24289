// Exports on a full disk (issue #22 item 2): each format, its file cut off at many sizes, fails
// with a message and leaves nothing under a real name and no temporary file; the process then
// exits normally (libhdf5's atexit close must not crash). And the export folder's rules (item
// 4), a running run refused unless partial is asked for (item 5), temporaries of killed
// exports removed at the next start (item 9).
//
// The full disk is RLIMIT_FSIZE (tests/support/file_size_limit.hpp), set in a child process:
// libhdf5 keeps library-wide state, and the exit of the process is part of what is tested.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <matio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "file_size_limit.hpp"
#include "wavebench/exports/export_folder.hpp"
#include "wavebench/exports/export_format.hpp"
#include "wavebench/exports/export_scratch.hpp"
#include "wavebench/exports/run_export.hpp"
#include "wavebench/exports/sample_export.hpp"

namespace wavebench::exports {
namespace {

namespace fs = std::filesystem;

// n synthetic samples with one extra channel, paged from memory.
ExportInput synthetic_input(std::uint64_t n, bool running = false) {
  ExportInput input;
  input.run_id = "20260101T000000Z-test";
  input.run = {{"id", input.run_id}, {"status", running ? "running" : "complete"}};
  input.results = {{"verdict", "PASS"}, {"stiffness", {{"k1", 1.5e4}, {"list", {1, 2, 3}}}}};
  input.page_records = 1000;
  input.sample_json = [](const storage::SyncSample& s, std::span<const storage::ChannelInfo>) {
    return nlohmann::json{{"index", s.index}, {"torque", s.torque_nm}};
  };
  input.pages = [n](std::uint64_t from, std::size_t count) {
    storage::SampleLogPage page;
    page.header.extra_channels = {{"oil_temp", "K"}};
    page.from = from;
    page.total_records = n;
    for (std::uint64_t i = from; i < n && i < from + count; ++i) {
      storage::SyncSample s;
      s.index = i;
      s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
      s.flags = storage::kAllChannelsValid;
      s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
      s.theta_in_rad = 0.001 * static_cast<double>(i);
      s.torque_nm = 10.0;
      s.extra[0] = 300.0;
      s.extra_valid = 1;
      page.samples.push_back(s);
    }
    return page;
  };
  return input;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("wavebench-hostile-exports-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

// In a child: export under a file size cap, then exit(0) (atexit handlers run: H5close). The
// child's status: 0 the export succeeded, 3 it failed with an exception, else a crash.
int export_in_child(ExportFormat format, std::uint64_t samples, rlim_t cap, const fs::path& dir) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    int code = 0;
    {
      testing::FileSizeLimit disk(cap);
      try {
        export_samples(synthetic_input(samples), format, dir);
      } catch (const std::exception&) {
        code = 3;
      }
    }
    std::exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 100 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

TEST(HostileExports, EveryFormatOnAFullDiskFailsCleanlyAndLeavesNothing) {
  int tried = 0, failed = 0;
  for (const auto format :
       {ExportFormat::kHdf5, ExportFormat::kMat, ExportFormat::kCsv, ExportFormat::kJson}) {
    for (const std::uint64_t samples : {0ULL, 1ULL, 5000ULL}) {
      for (const rlim_t cap : {rlim_t{0}, rlim_t{512}, rlim_t{2048}, rlim_t{4096}, rlim_t{20000},
                               rlim_t{100000}, rlim_t{300000}}) {
        const auto dir = fresh_dir("full");
        const int code = export_in_child(format, samples, cap, dir);
        ++tried;
        SCOPED_TRACE(std::string(export_format_name(format)) + " samples " +
                     std::to_string(samples) + " cap " + std::to_string(cap));
        ASSERT_TRUE(code == 0 || code == 3) << "child ended with " << code;
        const auto names = entries(dir);
        if (code == 3) {
          ++failed;
          EXPECT_TRUE(names.empty()) << names.front();
        } else {
          ASSERT_EQ(names.size(), 1u);
          EXPECT_EQ(names.front(), samples_file_name(format));
          // Whole: as large as the same export without a limit (libmatio reports no failed
          // write; a .mat cut short must not pass as written).
          const auto reference = fresh_dir("reference");
          ASSERT_EQ(export_in_child(format, samples, RLIM_INFINITY, reference), 0);
          EXPECT_EQ(fs::file_size(dir / names.front()),
                    fs::file_size(reference / samples_file_name(format)));
          fs::remove_all(reference);
        }
        fs::remove_all(dir);
      }
    }
  }
  std::cout << "full-disk exports tried " << tried << ", failed cleanly " << failed << "\n";
  EXPECT_GT(failed, tried / 3);
}

// A pid that was alive a moment ago and is not any more.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The whole folder on a full disk (item 2: samples.mat without run.json): a first export that
// fails leaves no folder; one that succeeds leaves all of it.
TEST(HostileExports, AFirstExportOnAFullDiskLeavesTheFolderCompleteOrAbsent) {
  int tried = 0, absent = 0;
  for (const auto format :
       {ExportFormat::kMat, ExportFormat::kHdf5, ExportFormat::kCsv, ExportFormat::kJson}) {
    for (const rlim_t cap :
         {rlim_t{1}, rlim_t{300}, rlim_t{3000}, rlim_t{50000}, rlim_t{200000}, rlim_t{2000000}}) {
      const auto parent = fresh_dir("folder");
      const auto dir = parent / "export";
      const pid_t pid = ::fork();
      if (pid == 0) {
        int code = 0;
        {
          testing::FileSizeLimit disk(cap);
          try {
            export_run(synthetic_input(20000), format, dir, false);
          } catch (const std::exception&) {
            code = 3;
          }
        }
        std::exit(code);
      }
      int status = 0;
      ::waitpid(pid, &status, 0);
      ++tried;
      SCOPED_TRACE(std::string(export_format_name(format)) + " cap " + std::to_string(cap));
      ASSERT_TRUE(WIFEXITED(status)) << "signal " << WTERMSIG(status);
      if (WEXITSTATUS(status) == 3) {
        ++absent;
        EXPECT_FALSE(fs::exists(dir));
      } else {
        ASSERT_EQ(WEXITSTATUS(status), 0);
        auto names = entries(dir);
        std::sort(names.begin(), names.end());
        EXPECT_EQ(names, (std::vector<std::string>{".wavebench-export", "results.json", "run.json",
                                                   samples_file_name(format)}));
      }
      fs::remove_all(parent);
    }
  }
  std::cout << "first exports on a full disk: " << tried << " tried, " << absent
            << " left no folder, the rest complete\n";
  EXPECT_GT(absent, 0);
  EXPECT_LT(absent, tried);
}

// Item 4: run B into run A's export folder is refused, and A's files stay as they were.
TEST(HostileExports, AnotherRunsExportFolderIsRefusedAndLeftAsItWas) {
  const auto dir = fresh_dir("two-runs") / "out";
  auto a = synthetic_input(100);
  export_run(a, ExportFormat::kCsv, dir, false);
  const std::string a_csv = read_text(dir / "samples.csv");
  auto b = synthetic_input(50);
  b.run_id = "20260101T000001Z-other";
  b.run["id"] = b.run_id;
  const auto refusal = export_folder_refusal(dir, b.run_id);
  ASSERT_TRUE(refusal.has_value());
  EXPECT_NE(refusal->find(a.run_id), std::string::npos) << *refusal;
  for (const auto format : {ExportFormat::kCsv, ExportFormat::kHdf5}) {
    EXPECT_THROW(export_run(b, format, dir, false), std::runtime_error);
  }
  auto names = entries(dir);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{".wavebench-export", "results.json", "run.json",
                                             "samples.csv"}));
  EXPECT_EQ(read_text(dir / "samples.csv"), a_csv);
  // The same run again is fine (an export folder is re-exported in another format).
  EXPECT_NO_THROW(export_run(a, ExportFormat::kJson, dir, false));
  fs::remove_all(dir.parent_path());
}

std::string hdf5_string_attribute(const fs::path& file, const char* name) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t attr = H5Aopen(f, name, H5P_DEFAULT);
  const hid_t type = H5Aget_type(attr);
  char* text = nullptr;
  std::string value = "(unreadable)";
  if (H5Aread(attr, type, &text) >= 0 && text) value = text;
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(attr);
  H5Fclose(f);
  return value;
}

double mat_scalar(const fs::path& file, const char* name) {
  mat_t* mat = Mat_Open(file.c_str(), MAT_ACC_RDONLY);
  if (!mat) return -1;
  matvar_t* v = Mat_VarRead(mat, name);
  const double value = v && v->data ? *static_cast<const double*>(v->data) : -1;
  Mat_VarFree(v);
  Mat_Close(mat);
  return value;
}

// Item 5: a running run is refused unless partial is asked for; then every format says so.
TEST(HostileExports, ARunningRunIsRefusedUnlessPartialAndThenEveryFileSaysSo) {
  const auto parent = fresh_dir("running");
  const auto running = synthetic_input(300, true);
  const auto refused = parent / "refused";
  try {
    export_run(running, ExportFormat::kCsv, refused, false);
    ADD_FAILURE() << "a running run was exported without --partial";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("--partial"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(refused));
  for (const auto format :
       {ExportFormat::kMat, ExportFormat::kHdf5, ExportFormat::kCsv, ExportFormat::kJson}) {
    const auto dir = parent / export_format_name(format);
    const auto summary = export_run(running, format, dir, true);
    EXPECT_TRUE(summary.partial);
    EXPECT_EQ(summary.samples, 300u);
    const auto file = dir / samples_file_name(format);
    switch (format) {
      case ExportFormat::kMat:
        EXPECT_EQ(mat_scalar(file, "partial"), 1.0);
        break;
      case ExportFormat::kHdf5:
        EXPECT_EQ(hdf5_string_attribute(file, "partial"), "true");
        break;
      case ExportFormat::kCsv:
        EXPECT_EQ(read_text(file).rfind("# partial export", 0), 0u);
        break;
      case ExportFormat::kJson: {
        const auto j = nlohmann::json::parse(read_text(file));
        EXPECT_EQ(j.value("partial", false), true);
        EXPECT_EQ(j["samples"].size(), 300u);
        break;
      }
    }
  }
  // A finished run's files say they are not partial.
  const auto done = parent / "done";
  export_run(synthetic_input(10), ExportFormat::kHdf5, done, false);
  EXPECT_EQ(hdf5_string_attribute(done / "samples.h5", "partial"), "false");
  export_run(synthetic_input(10), ExportFormat::kMat, done, false);
  EXPECT_EQ(mat_scalar(done / "samples.mat", "partial"), 0.0);
  fs::remove_all(parent);
}

// Item 9: what killed exports and downloads left is removed at the next start; nothing else.
TEST(HostileExports, TemporariesOfKilledExportsAndDownloadsAreRemovedAtTheNextStart) {
  const auto parent = fresh_dir("leftovers");
  const pid_t gone = dead_pid();
  const std::string tmp = ".tmp" + std::to_string(gone);
  // An export folder of run A with a killed export's temporaries (one 4 MB).
  const auto dir = parent / "export";
  const auto input = synthetic_input(10);
  export_run(input, ExportFormat::kCsv, dir, false);
  std::ofstream(dir / (".samples.h5" + tmp)) << std::string(4 << 20, 'x');
  std::ofstream(dir / (".run.json" + tmp)) << "{";
  std::ofstream(dir / (".samples.csv.tmp" + std::to_string(::getpid()))) << "live";
  export_run(input, ExportFormat::kJson, dir, false);
  EXPECT_FALSE(fs::exists(dir / (".samples.h5" + tmp)));
  EXPECT_FALSE(fs::exists(dir / (".run.json" + tmp)));
  EXPECT_TRUE(fs::exists(dir / (".samples.csv.tmp" + std::to_string(::getpid()))));

  // Download scratch folders: a dead daemon's go; a live one's, a foreign file's, others stay.
  const auto scratch = parent / "tmp";
  fs::create_directories(scratch);
  const auto stale = scratch / ("wavebench-export-" + std::to_string(gone) + "-0");
  fs::create_directories(stale);
  std::ofstream(stale / ("." + std::string("samples.h5") + tmp)) << std::string(1 << 20, 'x');
  std::ofstream(stale / "samples.csv") << "index\n";
  const auto empty_stale = scratch / ("wavebench-export-" + std::to_string(gone) + "-1");
  fs::create_directories(empty_stale);
  const auto foreign = scratch / ("wavebench-export-" + std::to_string(gone) + "-2");
  fs::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "mine";
  const auto live = scratch / export_scratch_name(7);
  fs::create_directories(live);
  const auto other = scratch / "wavebench-export-x-1";
  fs::create_directories(other);
  EXPECT_EQ(remove_stale_export_scratch(scratch), 2u);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(empty_stale));
  EXPECT_TRUE(fs::exists(foreign / "notes.txt"));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  fs::remove_all(parent);
}

}  // namespace
}  // namespace wavebench::exports
