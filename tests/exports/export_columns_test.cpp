// The export's columns cover exactly storage::kCoreChannels, then the extra ones: one double
// column per channel, NaN where it did not arrive. The test iterates the table, so a channel
// added to it is checked here without touching it.
#include "export_columns.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace wavebench::exports::detail {
namespace {

using storage::kCoreChannels;

TEST(ExportColumnsTable, OneColumnPerCoreChannelThenTheExtraOnes) {
  const std::vector<storage::ChannelInfo> extra{{"encoder_in", "rad"}, {"torque_2", "N*m"}};
  const auto columns = export_columns(extra);
  std::vector<const ExportColumn*> channels;
  for (const auto& c : columns)
    if (c.type == ColumnType::kDouble) channels.push_back(&c);
  ASSERT_EQ(channels.size(), kCoreChannels.size() + extra.size());
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
    EXPECT_EQ(channels[i]->name, kCoreChannels[i].name);
    EXPECT_EQ(channels[i]->unit, kCoreChannels[i].unit);
  }
  EXPECT_EQ(channels[kCoreChannels.size()]->name, "encoder_in");
  EXPECT_EQ(channels.back()->unit, "N*m");

  for (std::size_t missing = 0; missing < channels.size(); ++missing) {
    storage::SyncSample s;
    for (std::size_t i = 0; i < channels.size(); ++i)
      if (i != missing) s.set(i, 20.0 + static_cast<double>(i));
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const double v = channels[i]->real(s);
      if (i == missing)
        EXPECT_TRUE(std::isnan(v)) << channels[i]->name;
      else
        EXPECT_EQ(v, 20.0 + static_cast<double>(i)) << channels[i]->name;
    }
  }
}

TEST(ExportColumnsTable, CoreOnlyExportHasNoExtraValidColumn) {
  for (const auto& c : export_columns({})) EXPECT_NE(c.name, "extra_valid");
  std::size_t doubles = 0;
  for (const auto& c : export_columns({})) doubles += c.type == ColumnType::kDouble ? 1 : 0;
  EXPECT_EQ(doubles, kCoreChannels.size());
}

}  // namespace
}  // namespace wavebench::exports::detail
