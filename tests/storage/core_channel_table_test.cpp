// Every storage user of the core channels covers exactly storage::kCoreChannels: the channel
// list, the CSV and the sample log record. The tests iterate the table, so a channel added to
// it is checked in each without touching them.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "test_dir.hpp"
#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sample_csv.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (const char c : line) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

double f64_at(const std::vector<unsigned char>& r, std::size_t at) {
  std::uint64_t bits = 0;
  for (std::size_t k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(r[at + k]) << (8 * k);
  double v = 0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// A sample where only channel `only` arrived, with a value no other channel has.
SyncSample only_channel(std::size_t only) {
  SyncSample s;
  for (std::size_t i = 0; i < kCoreChannelCount; ++i) s.set(i, -1.0 - static_cast<double>(i));
  s.flags = 0;
  s.set(only, 100.5 + static_cast<double>(only));
  return s;
}

TEST(CoreChannelTable, ChannelListIsTheTable) {
  const auto listed = core_channels();
  ASSERT_EQ(listed.size(), kCoreChannels.size());
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
    EXPECT_EQ(listed[i].name, kCoreChannels[i].name) << i;
    EXPECT_EQ(listed[i].unit, kCoreChannels[i].unit) << i;
    // The extra-channel check refuses a core name: the table's names are reserved.
    EXPECT_THROW(check_extra_channels(std::vector<ChannelInfo>{listed[i]}), std::invalid_argument);
  }
}

TEST(CoreChannelTable, IndexedAccessReachesEachChannelAlone) {
  for (std::size_t i = 0; i < kMaxChannels; ++i) {
    SyncSample s;
    s.set(i, 7.25);
    for (std::size_t k = 0; k < kMaxChannels; ++k) EXPECT_EQ(s.arrived(k), k == i) << i << k;
    EXPECT_EQ(s.value(i), 7.25);
    s.clear(i);
    EXPECT_FALSE(s.arrived(i));
  }
  SyncSample s;
  s.set(kMaxChannels, 1.0);  // past the sample's channels: dropped
  for (std::size_t k = 0; k <= kMaxChannels; ++k) EXPECT_FALSE(s.arrived(k)) << k;
}

TEST(CoreChannelTable, CsvHasOneColumnPerChannelInTableOrder) {
  for (std::size_t only = 0; only < kCoreChannels.size(); ++only) {
    const std::vector<SyncSample> samples{only_channel(only)};
    std::ostringstream out;
    write_samples_csv(samples, out);
    std::istringstream in(out.str());
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    const auto names = split(header), fields = split(row);
    ASSERT_EQ(names.size(), 3 + kCoreChannels.size() + 3);
    ASSERT_EQ(fields.size(), names.size());
    for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
      EXPECT_EQ(names[3 + i], kCoreChannels[i].column);
      if (i == only)
        EXPECT_EQ(std::stod(fields[3 + i]), 100.5 + static_cast<double>(i)) << i;
      else
        EXPECT_EQ(fields[3 + i], "") << "channel " << i << " with only " << only << " arrived";
    }
  }
}

TEST(CoreChannelTable, SampleLogRecordHoldsEachChannelAtItsOffset) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  {
    SampleLogWriter writer(path);
    for (std::size_t only = 0; only < kCoreChannels.size(); ++only) {
      SyncSample s = only_channel(only);
      s.sync_counter = static_cast<std::uint32_t>(only + 1);
      const auto record = encode_sample_record(s);
      EXPECT_EQ(f64_at(record, kCoreChannels[only].record_offset), 100.5 + double(only)) << only;
      writer.append(s);
    }
  }
  const auto log = read_sample_log(path);
  ASSERT_EQ(log.samples.size(), kCoreChannels.size());
  for (std::size_t only = 0; only < kCoreChannels.size(); ++only) {
    const auto& s = log.samples[only];
    for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
      EXPECT_EQ(s.arrived(i), i == only) << i << " in record " << only;
      EXPECT_EQ(s.value(i), i == only ? 100.5 + double(i) : -1.0 - double(i)) << i;
    }
  }
}

}  // namespace
}  // namespace wavebench::storage
