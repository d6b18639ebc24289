// Sample logs written by main before the core channel table (tests/storage/fixtures): today's
// reader and encoder give back every byte, and today's CSV is the CSV that code wrote.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "test_dir.hpp"
#include "wavebench/storage/sample_csv.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {
namespace {

const std::filesystem::path kFixtures =
    std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "tests" / "storage" / "fixtures";

std::vector<unsigned char> bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << path;
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Fixture {
  const char* file;
  std::uint32_t version;
  std::size_t extras;
  std::size_t records;
};

class SampleLogFixture : public ::testing::TestWithParam<Fixture> {};

TEST_P(SampleLogFixture, ReadsAndReencodesByteForByte) {
  const auto& f = GetParam();
  const auto path = kFixtures / f.file;
  const auto file = bytes_of(path);
  const auto log = read_sample_log(path);
  EXPECT_EQ(log.header.version, f.version);
  EXPECT_EQ(log.header.extra_channels.size(), f.extras);
  ASSERT_EQ(log.samples.size(), f.records);
  EXPECT_EQ(log.torn_tail_bytes, 0u);
  EXPECT_FALSE(log.corrupt_record);

  auto again = encode_sample_log_header(log.header);
  for (const auto& s : log.samples) {
    const auto r = encode_sample_record(s, f.extras);
    again.insert(again.end(), r.begin(), r.end());
  }
  ASSERT_EQ(again.size(), file.size());
  for (std::size_t i = 0; i < file.size(); ++i)
    ASSERT_EQ(again[i], file[i]) << "first differing byte at " << i;

  const auto page = read_sample_log_page(path, 0, f.records);
  ASSERT_EQ(page.samples.size(), f.records);
  for (std::size_t i = 0; i < f.records; ++i) {
    EXPECT_EQ(encode_sample_record(page.samples[i], f.extras),
              encode_sample_record(log.samples[i], f.extras))
        << i;
  }
}

INSTANTIATE_TEST_SUITE_P(WrittenBeforeTheChannelTable, SampleLogFixture,
                         ::testing::Values(Fixture{"v2_two_extras.wbs", 2, 2, 12},
                                           Fixture{"v2_core_only.wbs", 2, 0, 6},
                                           Fixture{"v1_core_only.wbs", 1, 0, 4}),
                         [](const auto& fixture) {
                           std::string name = fixture.param.file;
                           return name.substr(0, name.find('.'));
                         });

TEST(SampleLogFixtureCsv, CsvIsTheOneWrittenBeforeTheChannelTable) {
  const auto dir = testing::fresh_test_dir();
  EXPECT_EQ(export_sample_log_csv(kFixtures / "v2_two_extras.wbs", dir / "samples.csv"), 12u);
  EXPECT_EQ(bytes_of(dir / "samples.csv"), bytes_of(kFixtures / "v2_two_extras.csv"));
}

TEST(SampleLogFixtureCsv, FixtureValuesReadAsWritten) {
  // Spot checks against the generator (fixtures/write_fixtures.cpp.txt), so the round trip
  // above cannot pass by reading garbage and writing the same garbage back.
  const auto log = read_sample_log(kFixtures / "v2_two_extras.wbs");
  const auto& s = log.samples[5];
  EXPECT_EQ(s.sync_counter, 16u);
  EXPECT_FALSE(s.arrived(channel::kThetaIn));
  EXPECT_FALSE(s.arrived(channel::kBrakeTorque));
  EXPECT_TRUE(s.arrived(channel::kTorque));
  EXPECT_DOUBLE_EQ(s.value(channel::kTorque), 7.5);
  EXPECT_DOUBLE_EQ(s.value(channel::kBrakeCurrent), 1.25);
  EXPECT_DOUBLE_EQ(s.value(kCoreChannelCount + 0), -37.5);
  EXPECT_DOUBLE_EQ(s.value(kCoreChannelCount + 1), 1e10 + 5);
  EXPECT_FALSE(log.samples[1].arrived(kCoreChannelCount + 1));
  EXPECT_TRUE(log.samples[1].arrived(kCoreChannelCount + 0));
  EXPECT_EQ(s.missed_before, 55u);
  EXPECT_TRUE(s.flags & kGapBefore);
}

}  // namespace
}  // namespace wavebench::storage
