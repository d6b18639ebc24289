#include "wavebench/storage/sample_log.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "sample_series.hpp"
#include "test_dir.hpp"
#include "wavebench/storage/sample_csv.hpp"

namespace wavebench::storage {
namespace {

using testing::make_sample;

TEST(SampleLog, RecordBytesAreLittleEndianWithTrailingChecksum) {
  SyncSample s;
  s.index = 0x0102030405060708ull;
  s.sync_counter = 0xA1B2C3D4u;
  s.theta_in_rad = 1.0;  // 0x3FF0000000000000
  const auto r = encode_sample_record(s);
  ASSERT_EQ(r.size(), kSampleLogRecordSize);
  EXPECT_EQ(r[0], 0x08);
  EXPECT_EQ(r[7], 0x01);
  EXPECT_EQ(r[8], 0xD4);
  EXPECT_EQ(r[11], 0xA1);
  EXPECT_EQ(r[24 + 6], 0xF0);
  EXPECT_EQ(r[24 + 7], 0x3F);
  // FNV-1a 32 of the first 92 bytes, computed here independently.
  std::uint32_t h = 2166136261u;
  for (int i = 0; i < 92; ++i) h = (h ^ r[static_cast<std::size_t>(i)]) * 16777619u;
  EXPECT_EQ(r[92] | (r[93] << 8) | (r[94] << 16) | (static_cast<std::uint32_t>(r[95]) << 24), h);
}

TEST(SampleLog, RoundTripsEverySampleAndCountsGaps) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  {
    SampleLogWriter writer(path);
    for (std::uint64_t i = 0; i < 1000; ++i) {
      if (i == 500 || i == 501) continue;  // two SYNC cycles lost
      writer.append(make_sample(i));
    }
    EXPECT_EQ(writer.gap_totals().gaps, 1u);
    EXPECT_EQ(writer.gap_totals().missed_cycles, 2u);
  }
  const auto log = read_sample_log(path);
  ASSERT_EQ(log.samples.size(), 998u);
  EXPECT_EQ(log.torn_tail_bytes, 0u);
  EXPECT_FALSE(log.corrupt_record);
  EXPECT_EQ(log.gaps.missed_cycles, 2u);
  EXPECT_EQ(log.header.counter_range.last, 240u);
  const auto& after_gap = log.samples[500];
  EXPECT_EQ(after_gap.index, 500u);
  EXPECT_EQ(after_gap.missed_before, 2u);
  EXPECT_NE(after_gap.flags & kGapBefore, 0u);
  EXPECT_DOUBLE_EQ(after_gap.theta_in_rad, 5.02);  // the sample of cycle 502, not filled
  EXPECT_EQ(log.samples[999 - 2].receive_time_ns, make_sample(999).receive_time_ns);
}

TEST(SampleLog, FlushesEveryNRecordsSoAReaderSeesThemBeforeClose) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  SampleLogWriterOptions options;
  options.flush_every_records = 10;
  options.flush_interval = std::chrono::hours(1);
  SampleLogWriter writer(path, options);
  for (std::uint64_t i = 0; i < 25; ++i) writer.append(make_sample(i));
  EXPECT_EQ(writer.records_flushed(), 20u);
  EXPECT_EQ(read_sample_log(path).samples.size(), 20u);
  writer.checkpoint();
  EXPECT_EQ(read_sample_log(path).samples.size(), 25u);
}

TEST(SampleLog, FlushIfDueWritesBufferedRecordsOnceTheIntervalHasPassed) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  SampleLogWriterOptions options;
  options.flush_every_records = 1000;
  options.flush_interval = std::chrono::milliseconds(0);  // always due: no clock in the test
  SampleLogWriter writer(path, options);
  writer.append(make_sample(0));  // due at append already
  EXPECT_EQ(writer.records_flushed(), 1u);
  options.flush_interval = std::chrono::hours(1);
  SampleLogWriter slow(dir / "slow.wbs", options);
  slow.append(make_sample(0));
  slow.flush_if_due();
  EXPECT_EQ(slow.records_flushed(), 0u);
  EXPECT_EQ(read_sample_log(dir / "slow.wbs").samples.size(), 0u);
}

TEST(SampleLog, TornLastRecordIsIgnoredAndReported) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  {
    SampleLogWriter writer(path);
    for (std::uint64_t i = 0; i < 10; ++i) writer.append(make_sample(i));
  }
  std::filesystem::resize_file(path, sample_log_header_size(0) + 9 * kSampleLogRecordSize + 40);
  const auto log = read_sample_log(path);
  EXPECT_EQ(log.samples.size(), 9u);
  EXPECT_EQ(log.torn_tail_bytes, 40u);
  EXPECT_DOUBLE_EQ(log.samples.back().torque_nm, 68.0);
}

TEST(SampleLog, CorruptRecordStopsReadingAndIsReported) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  {
    SampleLogWriter writer(path);
    for (std::uint64_t i = 0; i < 10; ++i) writer.append(make_sample(i));
  }
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(sample_log_header_size(0) + 6 * kSampleLogRecordSize + 30));
    f.put('\x55');
  }
  const auto log = read_sample_log(path);
  EXPECT_TRUE(log.corrupt_record);
  EXPECT_EQ(log.corrupt_at_index, 6u);
  EXPECT_EQ(log.samples.size(), 6u);
}

TEST(SampleLog, RejectsAFileThatIsNotASampleLog) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "other.bin";
  std::ofstream(path) << std::string(100, 'x');
  EXPECT_THROW(read_sample_log(path), std::runtime_error);
}

TEST(SampleCsv, InvalidChannelsAreEmptyAndGapsFlagged) {
  std::vector<SyncSample> samples = {make_sample(0), make_sample(1)};
  samples[1].flags = kAllChannelsValid & ~kTorqueValid;
  samples[1].flags |= kGapBefore;
  samples[1].index = 1;
  samples[1].missed_before = 4;
  std::ostringstream out;
  write_samples_csv(samples, out);
  std::istringstream in(out.str());
  std::string header, row0, row1;
  std::getline(in, header);
  std::getline(in, row0);
  std::getline(in, row1);
  EXPECT_EQ(header.substr(0, 30), "index,sync_counter,receive_tim");
  EXPECT_EQ(row0.rfind(",0,0,0"), row0.size() - 6);
  EXPECT_NE(row1.find(",0.01,-1e-04,10.47,,0.5,59.5,4,1,0"), std::string::npos) << row1;
}

TEST(SampleCsv, ExportWritesOneRowPerRecord) {
  const auto dir = testing::fresh_test_dir();
  {
    SampleLogWriter writer(dir / "s.wbs");
    for (std::uint64_t i = 0; i < 7; ++i) writer.append(make_sample(i));
  }
  EXPECT_EQ(export_sample_log_csv(dir / "s.wbs", dir / "s.csv"), 7u);
  std::ifstream in(dir / "s.csv");
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_EQ(lines, 8);
}

}  // namespace
}  // namespace wavebench::storage
