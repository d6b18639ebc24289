// The sample log on its own thread (issue #9): what the acquisition pushes reaches the file in
// order, a full queue drops and counts, a failed write is reported once from the writer thread.
#include "wavebench/storage/sample_log_thread.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "file_size_limit.hpp"
#include "sample_series.hpp"
#include "test_dir.hpp"

namespace wavebench::storage {
namespace {

namespace fs = std::filesystem;
using testing::make_sample;

struct RecordedFailures {
  std::mutex mutex;
  std::vector<int> errors;
  std::vector<std::thread::id> threads;
  SampleLogThread::FailureSink sink() {
    return [this](int error, const std::string&) {
      std::lock_guard lock(mutex);
      errors.push_back(error);
      threads.push_back(std::this_thread::get_id());
    };
  }
};

TEST(SampleLogThread, EveryPushedSampleReachesTheFileInOrder) {
  const auto path = testing::fresh_test_dir() / "samples.wbs";
  SampleLogWriter writer(path);
  RecordedFailures failures;
  SampleLogThread thread(writer, failures.sink());
  constexpr std::uint64_t kSamples = 5000;
  for (std::uint64_t i = 0; i < kSamples; ++i) ASSERT_TRUE(thread.try_push(make_sample(i)));
  thread.finish();
  thread.finish();  // idempotent
  writer.close();
  EXPECT_EQ(thread.samples_pushed(), kSamples);
  EXPECT_EQ(thread.samples_dropped(), 0u);
  EXPECT_EQ(thread.samples_not_written(), 0u);
  EXPECT_TRUE(failures.errors.empty());
  const auto log = read_sample_log(path);
  ASSERT_EQ(log.samples.size(), kSamples);
  for (std::uint64_t i = 0; i < kSamples; ++i) {
    EXPECT_EQ(log.samples[i].index, i);
    EXPECT_EQ(log.samples[i].theta_in_rad, make_sample(i).theta_in_rad);
  }
  fs::remove_all(path.parent_path());
}

TEST(SampleLogThread, AFullQueueDropsAndCountsInsteadOfWaiting) {
  const auto path = testing::fresh_test_dir() / "samples.wbs";
  SampleLogWriter writer(path);
  RecordedFailures failures;
  SampleLogThreadOptions options;
  options.queue_capacity = 1;
  SampleLogThread thread(writer, failures.sink(), options);
  constexpr std::uint64_t kSamples = 100000;  // far faster than one record at a time is taken
  std::uint64_t refused = 0;
  for (std::uint64_t i = 0; i < kSamples; ++i) refused += thread.try_push(make_sample(i)) ? 0 : 1;
  thread.finish();
  writer.close();
  EXPECT_GT(thread.samples_dropped(), 0u);
  EXPECT_EQ(thread.samples_dropped(), refused);
  const auto log = read_sample_log(path);
  EXPECT_EQ(log.samples.size() + thread.samples_dropped(), kSamples);  // none lost uncounted
  fs::remove_all(path.parent_path());
}

TEST(SampleLogThread, InLockstepTheProducerWaitsForTheWriterInsteadOfDropping) {
  const auto path = testing::fresh_test_dir() / "samples.wbs";
  SampleLogWriter writer(path);
  RecordedFailures failures;
  SampleLogThreadOptions options;
  options.queue_capacity = 64;
  options.lockstep_backlog = 4;  // simulated clock
  SampleLogThread thread(writer, failures.sink(), options);
  constexpr std::uint64_t kSamples = 20000;
  for (std::uint64_t i = 0; i < kSamples; ++i) ASSERT_TRUE(thread.try_push(make_sample(i)));
  thread.finish();
  writer.close();
  EXPECT_EQ(thread.samples_dropped(), 0u);
  EXPECT_EQ(read_sample_log(path).samples.size(), kSamples);
  fs::remove_all(path.parent_path());
}

TEST(SampleLogThread, AFailedWriteIsReportedOnceFromTheWriterThreadAndTheRestCounted) {
  const auto path = testing::fresh_test_dir() / "samples.wbs";
  SampleLogWriterOptions o;
  o.flush_every_records = 10;
  o.flush_interval = std::chrono::hours(1);
  o.checkpoint_every_records = 0;
  SampleLogWriter writer(path, o);
  RecordedFailures failures;
  {
    // Room for the header and 25 records: the flush after sample 29 fails part-way.
    wavebench::testing::FileSizeLimit limit(sample_log_header_size(0) + 25 * kSampleLogRecordSize);
    SampleLogThread thread(writer, failures.sink());
    for (std::uint64_t i = 0; i < 100; ++i) ASSERT_TRUE(thread.try_push(make_sample(i)));
    thread.finish();
    EXPECT_EQ(thread.samples_not_written(), 71u);  // sample 29 and the 70 after it
  }
  ASSERT_EQ(failures.errors.size(), 1u);
  EXPECT_EQ(failures.errors[0], EFBIG);
  EXPECT_NE(failures.threads[0], std::this_thread::get_id());
  EXPECT_EQ(writer.write_error(), EFBIG);
  EXPECT_NO_THROW(writer.close());
  EXPECT_EQ(read_sample_log(path).samples.size(), 25u);
  fs::remove_all(path.parent_path());
}

}  // namespace
}  // namespace wavebench::storage
