// One writer per runs folder for real (issue #22, item 3): with `.writer.lock` deleted, a second
// writer (another process opening a RunStore on the same folder, as a second wavebenchd does)
// used to take the folder and mark the first one's live run `incomplete`. The lock is now the
// folder's own: the second writer is refused with a message naming the folder, and the live
// run stays `running` in the index and in its status.json.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "wavebench/storage/run_store.hpp"

namespace wavebench::storage {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::temp_directory_path() /
                   ("wavebench-hostile-lock-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

// What the child saw opening its own store, passed back through a pipe: "refused: <message>"
// or "opened".
std::string open_in_another_process(const fs::path& root) {
  int out[2];
  if (::pipe(out) != 0) return "pipe failed";
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(out[0]);
    std::string said;
    try {
      RunStore second(root, "second");
      said = "opened";
    } catch (const RunStoreInUse& e) {
      said = std::string("refused: ") + e.what();
    } catch (const std::exception& e) {
      said = std::string("failed: ") + e.what();
    }
    const ssize_t n = ::write(out[1], said.data(), said.size());
    ::_exit(n == static_cast<ssize_t>(said.size()) ? 0 : 1);
  }
  ::close(out[1]);
  std::string said;
  char buf[512];
  for (ssize_t n; (n = ::read(out[0], buf, sizeof buf)) > 0;) said.append(buf, n);
  ::close(out[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  return said;
}

std::string status_file_says(const RunStore& store, const std::string& id) {
  std::ifstream in(store.paths(id).status);
  return nlohmann::json::parse(in, nullptr, false).value("status", std::string("?"));
}

TEST(HostileRunStoreLock, DeletingTheLockFileDoesNotLetASecondWriterIn) {
  const auto root = fresh_dir("deleted");
  RunStore first(root, "first");
  const auto live = first.create_run("dynamic", "SN-LOCK", "config: 1\n");
  int tries = 0, refused = 0;
  const auto t0 = std::chrono::steady_clock::now();
  // The lock file deleted, recreated empty, replaced by a folder: each time a second writer.
  for (const char* what : {"deleted", "recreated empty", "a folder in its place", "deleted"}) {
    std::error_code ec;
    fs::remove_all(root / kWriterLockFile, ec);
    if (std::string(what) == "recreated empty") std::ofstream(root / kWriterLockFile).flush();
    if (std::string(what) == "a folder in its place") fs::create_directory(root / kWriterLockFile);
    const auto said = open_in_another_process(root);
    ++tries;
    std::printf("lock file %s: second writer %s\n", what, said.c_str());
    ASSERT_EQ(said.rfind("refused: ", 0), 0u) << what << ": " << said;
    EXPECT_NE(said.find("run store " + root.string() + ": in use by "), std::string::npos) << said;
    ++refused;
    EXPECT_EQ(first.find_run(live)->status, RunStatus::kRunning) << what;
    EXPECT_EQ(status_file_says(first, live), "running") << what;
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%d second writers tried with the lock file gone or replaced, %d refused (%.0f ms)\n",
              tries, refused, ms);
  // The first writer still writes.
  first.finish_run(live, RunStatus::kComplete, "", true);
  EXPECT_EQ(first.find_run(live)->status, RunStatus::kComplete);
  fs::remove_all(root);
}

// While the lock file is there the refusal names the holder's process.
TEST(HostileRunStoreLock, TheRefusalNamesTheHoldersProcess) {
  const auto root = fresh_dir("named");
  RunStore first(root, "first");
  const auto said = open_in_another_process(root);
  EXPECT_NE(said.find("in use by process " + std::to_string(::getpid())), std::string::npos)
      << said;
  fs::remove_all(root);
}

// Stores of one process share the folder (the daemon's store and its readers), and the folder
// is free again once the last of them is gone.
TEST(HostileRunStoreLock, StoresOfOneProcessShareTheFolderAndReleaseIt) {
  const auto root = fresh_dir("shared");
  {
    RunStore a(root, "a");
    const auto id = a.create_run("static", "SN", "x");
    {
      const RunStore b(root, "b");
      EXPECT_TRUE(b.find_run(id));
    }
    EXPECT_EQ(open_in_another_process(root).rfind("refused: ", 0), 0u);
  }
  EXPECT_EQ(open_in_another_process(root), "opened");
  fs::remove_all(root);
}

}  // namespace
}  // namespace wavebench::storage
