// The sample log's version 2 (docs/formats/sample-log.md): channels named in the header, the
// bench's extra channels in every record, and version 1 logs written before it still read.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "sample_series.hpp"
#include "test_dir.hpp"
#include "wavebench/storage/sample_csv.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::storage {
namespace {

using testing::make_sample;

std::uint32_t fnv(const unsigned char* p, std::size_t n) {
  std::uint32_t h = 2166136261u;
  for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 16777619u;
  return h;
}

std::uint32_t u32_at(const std::vector<unsigned char>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) |
         (static_cast<std::uint32_t>(b[at + 3]) << 24);
}

TEST(SampleLogChannels, HeaderNamesCoreAndExtraChannelsInItsTable) {
  SampleLogHeader header;
  header.extra_channels = {{"theta_in_encoder", "rad"}, {"torque_2", "N*m"}};
  const auto h = encode_sample_log_header(header);
  // 64-byte prologue + count/pad + 8 channels x 48 + checksum/pad.
  ASSERT_EQ(h.size(), 64u + 8 + 8 * 48 + 8);
  EXPECT_EQ(u32_at(h, 8), 2u);
  EXPECT_EQ(u32_at(h, 12), h.size());
  EXPECT_EQ(u32_at(h, 16), 96u + 16);
  EXPECT_EQ(u32_at(h, 64), 8u);
  const auto name_at = [&](std::size_t i) {
    return std::string(reinterpret_cast<const char*>(&h[72 + 48 * i]));
  };
  EXPECT_EQ(name_at(0), "theta_in");
  EXPECT_EQ(name_at(3), "torque");
  EXPECT_EQ(name_at(6), "theta_in_encoder");
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&h[72 + 48 * 7 + 32])), "N*m");
  EXPECT_EQ(u32_at(h, 72 + 48 * 8), fnv(&h[64], 8 + 48 * 8));
}

TEST(SampleLogChannels, ExtraChannelsRoundTripWithTheirArrivalBits) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "samples.wbs";
  SampleLogWriterOptions options;
  options.extra_channels = {{"theta_in_encoder", "rad"}};
  {
    SampleLogWriter writer(path, options);
    for (std::uint64_t i = 0; i < 300; ++i) {
      auto s = make_sample(i);
      if (i % 7 != 0) {
        s.extra[0] = 0.25 * static_cast<double>(i);
        s.extra_valid = 1;
      }
      s.extra[1] = 99;  // not a channel of this log: never written
      s.extra_valid |= 2;
      writer.append(s);
    }
  }
  EXPECT_EQ(std::filesystem::file_size(path),
            sample_log_header_size(1) + 300 * sample_log_record_size(1));
  const auto log = read_sample_log(path);
  ASSERT_EQ(log.samples.size(), 300u);
  ASSERT_EQ(log.header.extra_channels.size(), 1u);
  EXPECT_EQ(log.header.extra_channels[0].name, "theta_in_encoder");
  EXPECT_EQ(log.header.version, 2u);
  for (std::uint64_t i = 0; i < 300; ++i) {
    const auto& s = log.samples[i];
    EXPECT_EQ(s.extra_arrived(0), i % 7 != 0) << i;
    EXPECT_FALSE(s.extra_arrived(1));
    if (i % 7 != 0) {
      EXPECT_DOUBLE_EQ(s.extra[0], 0.25 * static_cast<double>(i));
    }
    EXPECT_DOUBLE_EQ(s.theta_in_rad, make_sample(i).theta_in_rad);
  }
  const auto page = read_sample_log_page(path, 140, 3);
  ASSERT_EQ(page.samples.size(), 3u);
  EXPECT_EQ(page.total_records, 300u);
  EXPECT_DOUBLE_EQ(page.samples[1].extra[0], 0.25 * 141);
  EXPECT_EQ(page.header.extra_channels, log.header.extra_channels);

  std::ostringstream csv;
  write_samples_csv(log.samples, csv, log.header.extra_channels);
  const auto text = csv.str();
  EXPECT_NE(text.find("brake_torque_nm,theta_in_encoder_rad,missed_before"), std::string::npos);
}

// A version 1 log as the previous release wrote it, byte by byte: it still reads.
TEST(SampleLogChannels, VersionOneLogsStillRead) {
  const auto dir = testing::fresh_test_dir();
  const auto path = dir / "v1.wbs";
  {
    SampleLogHeader header;
    header.version = 1;
    header.counter_range = {1, 240};
    auto bytes = encode_sample_log_header(header);
    ASSERT_EQ(bytes.size(), 64u);
    for (std::uint64_t i = 0; i < 20; ++i) {
      auto s = make_sample(i);
      s.index = i;
      const auto r = encode_sample_record(s);
      ASSERT_EQ(r.size(), 96u);
      bytes.insert(bytes.end(), r.begin(), r.end());
    }
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
  }
  const auto log = read_sample_log(path);
  EXPECT_EQ(log.header.version, 1u);
  EXPECT_TRUE(log.header.extra_channels.empty());
  ASSERT_EQ(log.samples.size(), 20u);
  EXPECT_DOUBLE_EQ(log.samples[7].theta_out_rad, make_sample(7).theta_out_rad);
  const auto page = read_sample_log_page(path, 18, 10);
  EXPECT_EQ(page.total_records, 20u);
  ASSERT_EQ(page.samples.size(), 2u);
  EXPECT_EQ(page.samples[1].index, 19u);
}

TEST(SampleLogChannels, BadChannelTablesAndNamesAreRefused) {
  const auto dir = testing::fresh_test_dir();
  SampleLogWriterOptions options;
  options.extra_channels = {{"Theta In", "rad"}};
  EXPECT_THROW(SampleLogWriter(dir / "a.wbs", options), std::invalid_argument);
  options.extra_channels = {{"torque", "N*m"}};  // a core channel's name
  EXPECT_THROW(SampleLogWriter(dir / "b.wbs", options), std::invalid_argument);
  options.extra_channels.assign(kMaxExtraChannels + 1, {"x", "rad"});
  EXPECT_THROW(SampleLogWriter(dir / "c.wbs", options), std::invalid_argument);

  options.extra_channels = {{"theta_in_encoder", "rad"}};
  const auto path = dir / "d.wbs";
  { SampleLogWriter writer(path, options); }
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(72 + 48 * 6 + 3);  // a byte of the extra channel's name
    f.put('X');
  }
  try {
    read_sample_log(path);
    FAIL() << "a damaged channel table was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("channel table checksum"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wavebench::storage
