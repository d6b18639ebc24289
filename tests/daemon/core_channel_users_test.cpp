// The daemon's users of the core channels cover exactly storage::kCoreChannels: the sample
// JSON (both writers and the reader), the API's channel list and the run trace. The tests
// iterate the table, so a channel added to it is checked in each without touching them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "test_dir.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/run_trace.hpp"
#include "wavebench/daemon/sample_json.hpp"
#include "wavebench/storage/run_store.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::daemon::testing {
namespace {

using storage::kCoreChannels;

const std::set<std::string> kRecordKeys{"index", "sync_counter", "flags", "receive_time_ns",
                                        "missed_before"};

// Channel `i` arrived with 10 + i, unless it is `missing`.
storage::SyncSample sample_without(std::size_t missing) {
  storage::SyncSample s;
  s.index = 3;
  s.sync_counter = 4;
  s.receive_time_ns = 5;
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i)
    if (i != missing) s.set(i, 10.0 + static_cast<double>(i));
  return s;
}

TEST(CoreChannelUsers, SampleJsonHasOneKeyPerChannelNullWhereMissing) {
  for (std::size_t missing = 0; missing < kCoreChannels.size(); ++missing) {
    const auto s = sample_without(missing);
    const auto j = sample_to_json(s);
    std::string text;
    append_sample_json(text, s);
    EXPECT_EQ(nlohmann::json::parse(text), j) << text;
    std::set<std::string> keys;
    for (const auto& [key, value] : j.items()) keys.insert(key);
    auto expected = kRecordKeys;
    for (const auto& c : kCoreChannels) expected.insert(std::string(c.column));
    EXPECT_EQ(keys, expected);
    for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
      const auto& v = j[std::string(kCoreChannels[i].column)];
      if (i == missing)
        EXPECT_TRUE(v.is_null()) << kCoreChannels[i].column;
      else
        EXPECT_EQ(v, 10.0 + static_cast<double>(i)) << kCoreChannels[i].column;
    }
    const auto back = sample_from_json(j);
    for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
      EXPECT_EQ(back.arrived(i), i != missing) << i;
      if (i != missing) {
        EXPECT_EQ(back.value(i), 10.0 + static_cast<double>(i)) << i;
      }
    }
  }
}

TEST(CoreChannelUsers, ChannelListIsTheTableThenTheExtraOnes) {
  const std::vector<storage::ChannelInfo> extra{{"torque_2", "N*m"}};
  const auto list = channels_to_json(extra);
  ASSERT_EQ(list.size(), kCoreChannels.size() + 1);
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
    EXPECT_EQ(list[i]["name"], kCoreChannels[i].name);
    EXPECT_EQ(list[i]["unit"], kCoreChannels[i].unit);
    EXPECT_FALSE(list[i]["extra"].get<bool>());
  }
  EXPECT_EQ(list.back()["name"], "torque_2");
}

TEST(CoreChannelUsers, RunTraceOffersEachChannelWithItsValues) {
  const auto dir = fresh_test_dir();
  storage::RunStore store(dir / "runs", "test");
  const auto id = store.create_run("dynamic", "SN-1", "bench: test\n");
  {
    storage::SampleLogWriter writer(store.paths(id).samples);
    for (std::size_t k = 0; k < 20; ++k) {
      auto s = sample_without(k % kCoreChannels.size());
      s.sync_counter = static_cast<std::uint32_t>(k + 1);
      s.receive_time_ns = 1'000'000'000 + static_cast<std::int64_t>(k) * 1'000'000;
      writer.append(s);
    }
  }
  std::string names, listed = "te_arcsec";  // TE needs the run's gear: asked without it
  for (const auto& c : kCoreChannels) {
    names += (names.empty() ? "" : ",") + std::string(c.name);
    listed += ", " + std::string(c.name);
  }
  const auto r =
      run_trace(store, id, parse_http_target("/api/runs/" + id + "/trace?channels=" + names));
  ASSERT_EQ(r.status, 200) << r.body.dump();
  ASSERT_TRUE(r.body["full_resolution"].get<bool>());
  for (std::size_t i = 0; i < kCoreChannels.size(); ++i) {
    const auto& series = r.body["series"][std::string(kCoreChannels[i].name)];
    ASSERT_EQ(series.size(), 20u) << kCoreChannels[i].name;
    for (std::size_t k = 0; k < 20; ++k) {
      if (k % kCoreChannels.size() == i)
        EXPECT_TRUE(series[k].is_null()) << kCoreChannels[i].name << k;
      else
        EXPECT_EQ(series[k], 10.0 + static_cast<double>(i)) << kCoreChannels[i].name << k;
    }
  }
  // An unknown name is refused with the list of known ones: TE, then exactly the table.
  const auto bad =
      run_trace(store, id, parse_http_target("/api/runs/" + id + "/trace?channels=nope"));
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(bad.body.dump().find("expected a comma-separated list of " + listed), std::string::npos)
      << bad.body.dump();
}

}  // namespace
}  // namespace wavebench::daemon::testing
