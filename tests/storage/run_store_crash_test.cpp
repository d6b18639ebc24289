// The daemon killed with SIGKILL mid-run: after a restart the run is listed as incomplete and
// its samples up to the kill are readable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "test_dir.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {
namespace {

double theta_of(std::uint64_t i) {
  return 0.001 * static_cast<double>(i);
}

[[noreturn]] void child_writes_forever(const std::filesystem::path& root, int report_fd) {
  RunStore store(root, "crash-test");
  const auto id = store.create_run("dynamic_te", "SN-K", "speed_rpm: 100\n");
  SampleLogWriterOptions options;
  options.flush_every_records = 16;
  SampleLogWriter writer(store.paths(id).samples, options);
  std::uint64_t reported = 0;
  for (std::uint64_t i = 0;; ++i) {
    SyncSample s;
    s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
    s.flags = kAllChannelsValid;
    s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
    s.theta_in_rad = theta_of(i);
    s.theta_out_rad = -theta_of(i) / 80.0;
    s.torque_nm = static_cast<double>(i);
    writer.append(s);
    // Tell the parent how many records are on their way to disk for sure.
    if (writer.records_flushed() >= reported + 16) {
      reported = writer.records_flushed();
      const std::string line = id + " " + std::to_string(reported) + "\n";
      if (::write(report_fd, line.data(), line.size()) < 0) _exit(2);
    }
  }
}

TEST(RunStoreCrash, SigkilledWriterLeavesAnIncompleteRunWithEveryFlushedSample) {
  const auto root = testing::fresh_test_dir();
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(fds[0]);
    child_writes_forever(root, fds[1]);
  }
  ::close(fds[1]);
  FILE* reports = ::fdopen(fds[0], "r");
  ASSERT_NE(reports, nullptr);
  char id_buf[64] = {};
  unsigned long long flushed = 0;
  while (flushed < 5000) {
    ASSERT_EQ(std::fscanf(reports, "%63s %llu", id_buf, &flushed), 2) << "child stopped";
  }
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  std::fclose(reports);

  RunStore store(root, "after-restart");
  const std::string id = id_buf;
  const auto run = store.find_run(id);
  ASSERT_TRUE(run);
  EXPECT_EQ(run->status, RunStatus::kIncomplete);
  RunQuery incomplete;
  incomplete.status = RunStatus::kIncomplete;
  ASSERT_EQ(store.list_runs(incomplete).size(), 1u);

  const auto log = read_sample_log(store.paths(id).samples);
  EXPECT_FALSE(log.corrupt_record);
  ASSERT_GE(log.samples.size(), flushed);
  for (std::size_t i = 0; i < log.samples.size(); ++i) {
    ASSERT_EQ(log.samples[i].index, i);
    ASSERT_DOUBLE_EQ(log.samples[i].theta_in_rad, theta_of(i));
    ASSERT_DOUBLE_EQ(log.samples[i].torque_nm, static_cast<double>(i));
  }
  EXPECT_EQ(log.gaps.missed_cycles, 0u);
}

}  // namespace
}  // namespace wavebench::storage
