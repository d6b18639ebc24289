// read_sample_log_page: a page of the log equals the same records of the full reader at the
// start, the middle, the end, past the end, on a torn tail and on a corrupt record, and reads
// only the header and the page (issue #8: a page of a 16 M-sample run read the whole log).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <system_error>

#include "file_size_limit.hpp"
#include "sample_series.hpp"
#include "test_dir.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {
namespace {

namespace fs = std::filesystem;

using testing::make_sample;

fs::path write_log(const fs::path& dir, std::uint64_t records) {
  const auto path = dir / "samples.wbs";
  SampleLogWriterOptions o;
  o.flush_every_records = 4096;
  o.checkpoint_every_records = 0;
  SampleLogWriter writer(path, o);
  for (std::uint64_t i = 0; i < records; ++i) writer.append(make_sample(i));
  writer.close();
  return path;
}

void expect_same(const SyncSample& a, const SyncSample& b) {
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.sync_counter, b.sync_counter);
  EXPECT_EQ(a.flags, b.flags);
  EXPECT_EQ(a.receive_time_ns, b.receive_time_ns);
  EXPECT_EQ(a.theta_in_rad, b.theta_in_rad);
  EXPECT_EQ(a.theta_out_rad, b.theta_out_rad);
  EXPECT_EQ(a.torque_nm, b.torque_nm);
  EXPECT_EQ(a.missed_before, b.missed_before);
}

// The page against the full reader's records [from, from + count).
void expect_page_matches(const fs::path& path, std::uint64_t from, std::size_t count) {
  SCOPED_TRACE("page from " + std::to_string(from) + " count " + std::to_string(count));
  const auto full = read_sample_log(path);
  const auto page = read_sample_log_page(path, from, count);
  const std::uint64_t end = std::min<std::uint64_t>(from + count, full.samples.size());
  const std::uint64_t expected = from < end ? end - from : 0;
  ASSERT_EQ(page.samples.size(), expected);
  for (std::size_t i = 0; i < page.samples.size(); ++i) {
    expect_same(page.samples[i], full.samples[from + i]);
  }
  EXPECT_EQ(page.from, from);
  EXPECT_EQ(page.torn_tail_bytes, full.torn_tail_bytes);
  EXPECT_EQ(page.header.counter_range.first, full.header.counter_range.first);
  EXPECT_EQ(page.header.created_ns, full.header.created_ns);
}

TEST(SampleLogPage, EqualsTheFullReaderAtTheStartMiddleEndAndPastTheEnd) {
  const auto path = write_log(testing::fresh_test_dir(), 1000);
  expect_page_matches(path, 0, 10);
  expect_page_matches(path, 500, 100);
  expect_page_matches(path, 990, 10);
  expect_page_matches(path, 995, 50);  // runs over the end: the last 5
  expect_page_matches(path, 1000, 10);
  expect_page_matches(path, 123456, 10);
  expect_page_matches(path, 0, 0);
  const auto page = read_sample_log_page(path, 1000, 10);
  EXPECT_EQ(page.total_records, 1000u);
  EXPECT_TRUE(page.samples.empty());
  EXPECT_FALSE(page.corrupt_record);
}

TEST(SampleLogPage, ATornTailIsReportedAndNotReturned) {
  const auto path = write_log(testing::fresh_test_dir(), 300);
  {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    out << std::string(37, '\x5a');  // a record cut short by a crash
  }
  const auto page = read_sample_log_page(path, 290, 100);
  EXPECT_EQ(page.total_records, 300u);
  EXPECT_EQ(page.torn_tail_bytes, 37u);
  ASSERT_EQ(page.samples.size(), 10u);
  EXPECT_EQ(page.samples.back().index, 299u);
  expect_page_matches(path, 290, 100);
}

TEST(SampleLogPage, StopsBeforeACorruptRecordAsTheFullReaderDoes) {
  const auto path = write_log(testing::fresh_test_dir(), 1000);
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(
        static_cast<std::streamoff>(sample_log_header_size(0) + 500 * kSampleLogRecordSize + 30));
    f.put('\x7f');
  }
  const auto full = read_sample_log(path);
  ASSERT_TRUE(full.corrupt_record);
  ASSERT_EQ(full.corrupt_at_index, 500u);

  const auto page = read_sample_log_page(path, 490, 20);
  EXPECT_TRUE(page.corrupt_record);
  EXPECT_EQ(page.corrupt_at_index, 500u);
  ASSERT_EQ(page.samples.size(), 10u);
  for (std::size_t i = 0; i < page.samples.size(); ++i) {
    expect_same(page.samples[i], full.samples[490 + i]);
  }
  // A page before the corrupt record does not see it, and needs not.
  const auto before = read_sample_log_page(path, 0, 100);
  EXPECT_FALSE(before.corrupt_record);
  EXPECT_EQ(before.samples.size(), 100u);
}

TEST(SampleLogPage, RefusesAnOversizedPageAndABadHeader) {
  const auto dir = testing::fresh_test_dir();
  const auto path = write_log(dir, 10);
  EXPECT_THROW(read_sample_log_page(path, 0, kMaxSampleLogPageRecords + 1), std::invalid_argument);
  {
    std::ofstream out(dir / "short.wbs", std::ios::binary);
    out << "WBSAMPL1";
  }
  EXPECT_THROW(read_sample_log_page(dir / "short.wbs", 0, 10), std::runtime_error);
  EXPECT_THROW(read_sample_log_page(dir / "missing.wbs", 0, 10), std::runtime_error);
}

// Bytes this process has read through read(2) and pread(2) so far (Linux).
std::optional<std::uint64_t> bytes_read_by_process() {
  std::ifstream in("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (in >> key >> value) {
    if (key == "rchar:") return value;
  }
  return std::nullopt;
}

TEST(SampleLogPage, APageOfALargeLogReadsOnlyTheHeaderAndThePage) {
  constexpr std::uint64_t kRecords = 2'000'000;  // 192 MB
  const auto dir = testing::fresh_test_dir();
  const auto path = write_log(dir, kRecords);
  ASSERT_EQ(fs::file_size(path), sample_log_header_size(0) + kRecords * kSampleLogRecordSize);
  const auto before = bytes_read_by_process();
  if (!before) GTEST_SKIP() << "no /proc/self/io to count the bytes read";
  const auto page = read_sample_log_page(path, 1'234'567, 100);
  const auto after = bytes_read_by_process();
  ASSERT_TRUE(after);
  const std::uint64_t read = *after - *before;
  std::printf("page of 100 records of %llu: %llu bytes read\n",
              static_cast<unsigned long long>(kRecords), static_cast<unsigned long long>(read));
  EXPECT_LE(read, sample_log_header_size(0) + 100 * kSampleLogRecordSize + 4096);
  EXPECT_EQ(page.total_records, kRecords);
  ASSERT_EQ(page.samples.size(), 100u);
  for (std::size_t i = 0; i < page.samples.size(); ++i) {
    auto expected = make_sample(1'234'567 + i);
    expected.index = 1'234'567 + i;  // stamped by the writer
    expect_same(page.samples[i], expected);
  }
  fs::remove_all(dir);
}

TEST(SampleLogWriter, AfterAFailedWriteItStopsWritingAndClosesWithoutThrowing) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  SampleLogWriterOptions o;
  o.flush_every_records = 10;
  o.checkpoint_every_records = 0;
  SampleLogWriter writer(path, o);
  std::uint64_t appended = 0;
  {
    // Room for the header and 25 records: the third flush fails part-way.
    wavebench::testing::FileSizeLimit limit(sample_log_header_size(0) + 25 * kSampleLogRecordSize);
    try {
      for (; appended < 100; ++appended) writer.append(make_sample(appended));
      FAIL() << "no write failed";
    } catch (const std::system_error& e) {
      EXPECT_EQ(e.code().value(), EFBIG);
    }
  }
  EXPECT_EQ(writer.write_error(), EFBIG);
  EXPECT_EQ(writer.records_flushed(), 20u);
  const auto size_after_failure = fs::file_size(path);
  // Limit lifted: the writer still does not touch the file again.
  EXPECT_THROW(writer.append(make_sample(appended)), std::system_error);
  EXPECT_THROW(writer.flush(), std::system_error);
  EXPECT_NO_THROW(writer.close());
  EXPECT_EQ(fs::file_size(path), size_after_failure);
  const auto log = read_sample_log(path);
  EXPECT_EQ(log.samples.size(), 25u);  // the 25 that fitted
  EXPECT_EQ(log.torn_tail_bytes, 0u);
  EXPECT_FALSE(log.corrupt_record);
}

}  // namespace
}  // namespace wavebench::storage
