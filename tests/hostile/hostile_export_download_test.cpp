// The daemon's export download (issue #22 items 2, 5): an HDF5 (or any) download that fails on
// a full disk answers an error and the process still exits cleanly afterwards (it died of
// SIGSEGV at SIGTERM: libhdf5's teardown at exit); a running run's download is refused with
// 409 unless partial=1.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "file_size_limit.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/run_export_download.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon {
namespace {

namespace fs = std::filesystem;

struct StoreWithRun {
  fs::path root;
  std::unique_ptr<storage::RunStore> store;
  std::string id;

  explicit StoreWithRun(const std::string& name, std::uint64_t samples) {
    root = fs::temp_directory_path() /
           ("wavebench-hostile-download-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(root);
    store = std::make_unique<storage::RunStore>(root, "test");
    id = store->create_run("dynamic", "SN1", "bench: {}\n");
    storage::SampleLogWriter log(store->paths(id).samples);
    for (std::uint64_t i = 0; i < samples; ++i) {
      storage::SyncSample s;
      s.sync_counter = static_cast<std::uint32_t>(i % 200 + 1);
      s.flags = storage::kAllChannelsValid;
      s.torque_nm = 1.0;
      log.append(s);
    }
  }
  ~StoreWithRun() {
    store.reset();
    std::error_code ec;
    fs::remove_all(root, ec);
  }
  ApiResponse download(const std::string& query) const {
    return run_export_download(*store, id,
                               parse_http_target("/api/runs/" + id + "/export?" + query));
  }
};

TEST(HostileExportDownload, ARunningRunIsRefusedUnlessPartial) {
  StoreWithRun s("running", 500);
  for (const std::string format : {"csv", "json", "mat", "hdf5"}) {
    const auto refused = s.download("format=" + format);
    EXPECT_EQ(refused.status, 409) << format;
    EXPECT_NE(refused.body.dump().find("partial=1"), std::string::npos) << refused.body.dump();
    EXPECT_EQ(s.download("format=" + format + "&partial=1").status, 200) << format;
  }
  EXPECT_EQ(s.download("format=csv&partial=yes").status, 400);
  const auto csv = s.download("format=csv&partial=1");
  ASSERT_TRUE(csv.chunks);  // sent in chunks (run_export_download.hpp)
  std::string body;
  while (auto chunk = csv.chunks->next()) body += *chunk;
  EXPECT_EQ(body.rfind("# partial export", 0), 0u);
}

// In a child, so that its exit (libhdf5's state after the failure) is what is checked.
TEST(HostileExportDownload, AFailedDownloadOnAFullDiskLeavesTheProcessAbleToExit) {
  StoreWithRun s("full", 20000);
  int tried = 0;
  for (const std::string format : {"hdf5", "mat", "csv", "json"}) {
    for (const rlim_t cap : {rlim_t{600}, rlim_t{5000}, rlim_t{200000}}) {
      const pid_t pid = ::fork();
      if (pid == 0) {
        int code = 0;
        {
          wavebench::testing::FileSizeLimit disk(cap);
          try {
            const auto r = s.download("format=" + format + "&partial=1");
            code = r.status == 200 ? 0 : 3;
          } catch (const std::exception&) {
            code = 3;
          }
        }
        std::exit(code);  // as the daemon's main returns after SIGTERM: atexit handlers run
      }
      int status = 0;
      ::waitpid(pid, &status, 0);
      ++tried;
      EXPECT_TRUE(WIFEXITED(status)) << format << " cap " << cap << ": signal " << WTERMSIG(status);
      if (WIFEXITED(status)) {
        EXPECT_EQ(WEXITSTATUS(status), 3) << format << " cap " << cap;
      }
    }
  }
  std::cout << "downloads on a full disk: " << tried << "\n";
}

}  // namespace
}  // namespace wavebench::daemon
