// The daemon's small parts: targets, the live ring buffer, the token, samples as JSON, options.
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "test_dir.hpp"
#include "wavebench/daemon/api_token.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/daemon_options.hpp"
#include "wavebench/daemon/daemon_state.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/daemon/live_sample_buffer.hpp"
#include "wavebench/daemon/low_priority_reads.hpp"
#include "wavebench/daemon/realtime_scheduling.hpp"
#include "wavebench/daemon/sample_json.hpp"

namespace wavebench::daemon::testing {
namespace {

TEST(HttpTarget, SplitsPathAndDecodesQuery) {
  const auto t = parse_http_target("/api/runs/ab%20c/samples?from=10&limit=5&x=a+b%2Fc&flag");
  ASSERT_EQ(t.segments.size(), 4u);
  EXPECT_EQ(t.segments[2], "ab c");
  EXPECT_EQ(t.query.at("from"), "10");
  EXPECT_EQ(t.query.at("x"), "a b/c");
  EXPECT_EQ(t.query.at("flag"), "");
  EXPECT_THROW(parse_http_target("/api/%zz"), std::invalid_argument);
  EXPECT_THROW(parse_http_target("/api/%4"), std::invalid_argument);
  EXPECT_EQ(url_decode(url_encode("a b/c?d=é")), "a b/c?d=é");
}

storage::SyncSample sample_at(double v) {
  storage::SyncSample s;
  s.theta_in_rad = v;
  s.flags = storage::kAllChannelsValid;
  return s;
}

TEST(LiveSampleBuffer, ReturnsWhatArrivedSinceAndCountsWhatLeftTheBuffer) {
  LiveSampleBuffer buffer(4);
  auto slice = buffer.since(0, 10);
  EXPECT_TRUE(slice.samples.empty());
  EXPECT_EQ(slice.next_seq, 0u);
  for (int i = 0; i < 3; ++i) buffer.on_sample(sample_at(i));
  slice = buffer.since(1, 10);
  ASSERT_EQ(slice.samples.size(), 2u);
  EXPECT_EQ(slice.samples[0].seq, 1u);
  EXPECT_EQ(slice.samples[0].sample.theta_in_rad, 1.0);
  EXPECT_EQ(slice.next_seq, 3u);
  EXPECT_EQ(slice.missed, 0u);
  for (int i = 3; i < 10; ++i) buffer.on_sample(sample_at(i));
  slice = buffer.since(3, 10);  // 3..5 have been overwritten
  ASSERT_EQ(slice.samples.size(), 4u);
  EXPECT_EQ(slice.samples.front().seq, 6u);
  EXPECT_EQ(slice.samples.back().sample.theta_in_rad, 9.0);
  EXPECT_EQ(slice.missed, 3u);
  slice = buffer.since(6, 2);  // only the newest two
  ASSERT_EQ(slice.samples.size(), 2u);
  EXPECT_EQ(slice.samples.front().seq, 8u);
  EXPECT_EQ(slice.missed, 2u);
  EXPECT_TRUE(buffer.since(10, 5).samples.empty());
  EXPECT_TRUE(buffer.since(99, 5).samples.empty());
  EXPECT_EQ(buffer.total(), 10u);
}

TEST(LiveSampleBuffer, ReadersRacingTheWriterGetWholeSamplesOrCountThemMissed) {
  LiveSampleBuffer buffer(16);  // small, so that the writer laps the readers often
  constexpr std::uint64_t kSamples = 200000;
  std::atomic<bool> done{false};
  std::atomic<std::uint64_t> torn{0};
  std::atomic<std::uint64_t> unaccounted{0};
  std::vector<std::thread> readers;
  for (int r = 0; r < 3; ++r) {
    readers.emplace_back([&] {
      std::uint64_t since = 0;
      while (!done.load()) {
        const auto slice = buffer.since(since, 0);
        for (const auto& live : slice.samples) {
          // Every field of sample seq is derived from seq: a torn copy mixes two samples.
          const auto v = static_cast<double>(live.seq);
          if (live.sample.theta_in_rad != v || live.sample.theta_out_rad != -v ||
              live.sample.torque_nm != 2 * v || live.sample.sync_counter != live.seq % 1000) {
            ++torn;
          }
        }
        if (slice.samples.size() + slice.missed != slice.next_seq - since) ++unaccounted;
        since = slice.next_seq;
      }
    });
  }
  for (std::uint64_t i = 0; i < kSamples; ++i) {
    storage::SyncSample s = sample_at(static_cast<double>(i));
    s.theta_out_rad = -static_cast<double>(i);
    s.torque_nm = 2 * static_cast<double>(i);
    s.sync_counter = static_cast<std::uint32_t>(i % 1000);
    buffer.on_sample(s);  // never waits for a reader
  }
  done = true;
  for (auto& t : readers) t.join();
  EXPECT_EQ(torn.load(), 0u);
  EXPECT_EQ(unaccounted.load(), 0u);
  EXPECT_EQ(buffer.total(), kSamples);
}

TEST(ApiToken, CreatedOwnerOnlyAndReadBack) {
  const auto dir = fresh_test_dir();
  const auto path = dir / "sub" / "daemon.token";
  const auto token = load_or_create_token(path);
  EXPECT_EQ(token.size(), 64u);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_EQ(load_or_create_token(path), token);  // not replaced
  EXPECT_EQ(read_token(path), token);
  EXPECT_NE(load_or_create_token(dir / "other.token"), token);
  EXPECT_THROW(read_token(dir / "missing.token"), std::runtime_error);
  std::ofstream(dir / "empty.token") << "\n";
  EXPECT_THROW(read_token(dir / "empty.token"), TokenFileRefused);
}

TEST(ApiToken, BearerMustMatchExactly) {
  EXPECT_TRUE(bearer_matches("Bearer abc123", "abc123"));
  EXPECT_FALSE(bearer_matches("Bearer abc124", "abc123"));
  EXPECT_FALSE(bearer_matches("Bearer abc1234", "abc123"));
  EXPECT_FALSE(bearer_matches("bearer abc123", "abc123"));
  EXPECT_FALSE(bearer_matches("abc123", "abc123"));
  EXPECT_FALSE(bearer_matches("Bearer ", ""));
}

TEST(SampleJson, RoundTripsAndMissingChannelsAreNull) {
  storage::SyncSample s;
  s.index = 7;
  s.sync_counter = 240;
  s.flags = storage::kAllChannelsValid & ~storage::kTorqueValid;
  s.receive_time_ns = 1'234'567'890'123;
  s.theta_in_rad = 0.1 + 1e-12;
  s.theta_out_rad = -3.0e-3;
  s.input_speed_rad_s = 10.471975511965978;
  s.torque_nm = 99;  // not valid: must not appear
  s.brake_current_a = 0.5;
  s.brake_torque_nm = 60;
  s.missed_before = 2;
  const auto j = sample_to_json(s);
  EXPECT_TRUE(j["torque_nm"].is_null());
  const auto back = sample_from_json(nlohmann::json::parse(j.dump()));
  EXPECT_EQ(back.index, 7u);
  EXPECT_EQ(back.sync_counter, 240u);
  EXPECT_EQ(back.flags, s.flags);
  EXPECT_EQ(back.receive_time_ns, s.receive_time_ns);
  EXPECT_EQ(back.theta_in_rad, s.theta_in_rad);  // exact: JSON keeps round-trip digits
  EXPECT_EQ(back.input_speed_rad_s, s.input_speed_rad_s);
  EXPECT_EQ(back.missed_before, 2u);
  EXPECT_THROW(sample_from_json({{"index", 1}}), std::invalid_argument);
}

TEST(SampleJson, TextEqualsTheObjectsDump) {
  // The samples page writes its samples as text (append_sample_json): parsed, the same JSON as
  // sample_to_json, number types included, with extra channels, absent values and NaN.
  const std::vector<storage::ChannelInfo> extra = {{"encoder \"B\"", "rad"}, {"t2", "N*m"}};
  std::vector<std::string> keys;
  for (const auto& c : extra) keys.push_back(nlohmann::json(c.name).dump());
  for (int k = 0; k < 4; ++k) {
    storage::SyncSample s;
    s.index = 18'446'744'073'709'551'615ULL - static_cast<std::uint64_t>(k);
    s.sync_counter = 240;
    s.flags = k == 1 ? 0u : storage::kAllChannelsValid & ~(1u << k);
    s.receive_time_ns = -1'234'567'890'123 + k;
    s.theta_in_rad = 0.1 + 1e-12;
    s.theta_out_rad = k == 2 ? std::nan("") : -3.0e-3;
    s.input_speed_rad_s = 1e300;
    s.torque_nm = 60;  // whole: stays a float
    s.brake_current_a = 5e-324;
    s.brake_torque_nm = -0.0;
    s.missed_before = 4'000'000'000u;
    s.extra[0] = 1.5;
    s.extra[1] = 2;
    s.extra_valid = k == 3 ? 1u : 3u;
    std::string text;
    append_sample_json(text, s, keys);
    const auto parsed = nlohmann::json::parse(text);
    const auto want = nlohmann::json::parse(sample_to_json(s, extra).dump());  // as sent
    EXPECT_EQ(parsed, want) << text << "\n" << want.dump();
    for (const auto& [key, value] : want.items()) {
      EXPECT_EQ(parsed[key].type(), value.type()) << key;
    }
  }
}

TEST(DaemonOptions, ListenAddress) {
  auto a = parse_listen_address("127.0.0.1:8470");
  EXPECT_EQ(a.host, "127.0.0.1");
  EXPECT_EQ(a.port, 8470);
  a = parse_listen_address(":0");
  EXPECT_EQ(a.host, "127.0.0.1");
  EXPECT_EQ(a.port, 0);
  EXPECT_EQ(parse_listen_address("[::1]:9000").host, "::1");
  for (const char* bad : {"8470", "host:", "host:70000", "host:12x"}) {
    try {
      parse_listen_address(bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--listen"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos);
    }
  }
}

TEST(DaemonClient, Url) {
  auto e = parse_daemon_url("http://127.0.0.1:8470");
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, "8470");
  e = parse_daemon_url("localhost");
  EXPECT_EQ(e.port, "8470");
  EXPECT_THROW(parse_daemon_url("https://x:1"), std::invalid_argument);
  EXPECT_THROW(parse_daemon_url("http://x:99999"), std::invalid_argument);
  EXPECT_THROW(parse_daemon_url("http://x:1/api"), std::invalid_argument);
}

TEST(DaemonClient, NoDaemonIsReportedAsUnreachable) {
  // Port 1 on loopback: nothing listens there without root.
  DaemonClient client("http://127.0.0.1:1", "");
  EXPECT_THROW(client.get("/api/status"), DaemonUnreachable);
}

TEST(DaemonState, FromLifecycleAndRun) {
  using bench::BenchLifecycle;
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kUnconfigured, false), DaemonState::kIdle);
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kInactive, false), DaemonState::kReady);
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kActive, false), DaemonState::kReady);
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kActive, true), DaemonState::kRunning);
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kInactive, true), DaemonState::kRunning);
  EXPECT_EQ(daemon_state_of(BenchLifecycle::kFault, true), DaemonState::kFault);
  EXPECT_STREQ(daemon_state_name(DaemonState::kFault), "fault");
}

}  // namespace
}  // namespace wavebench::daemon::testing

namespace wavebench::daemon {
namespace {

TEST(LowPriorityReads, AnswersRefusesWhenAllAreBusyAndTurnsExceptionsInto500) {
  LowPriorityReads reads(2);
  EXPECT_EQ(reads.run([] { return ApiResponse{200, {{"ok", true}}}; })->body["ok"], true);
  const auto failed = reads.run([]() -> ApiResponse { throw std::runtime_error("disk gone"); });
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->status, 500);
  EXPECT_EQ(failed->body["detail"], "disk gone");

  // Two reads held busy: a third is refused at once rather than queued behind them.
  std::promise<void> release;
  auto released = release.get_future().share();
  std::atomic<int> running{0};
  const auto hold = [&] {
    ++running;
    released.wait();
    return ApiResponse{200, nullptr};
  };
  std::thread a([&] { reads.run(hold); });
  std::thread b([&] { reads.run(hold); });
  // Both reads start right after the two above returned: a reader that had answered but not
  // yet counted itself idle refused one of them once, and this loop then spun for ever.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (running < 2 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  const bool both_running = running == 2;
  const bool third_refused = !reads.run([] { return ApiResponse{200, nullptr}; }).has_value();
  release.set_value();
  a.join();
  b.join();
  ASSERT_TRUE(both_running) << "a read was refused while a reader was free";
  EXPECT_TRUE(third_refused);
  EXPECT_TRUE(reads.run([] { return ApiResponse{204, nullptr}; }).has_value());
}

// The bench thread's helpers (twin, sample log writer, post-run analysis) must not inherit its
// SCHED_FIFO: inherited, a post-run analysis held a core at real-time priority and the
// simulated brake, starved, tripped its watchdog (CI, run 4 of 5 in a row).
TEST(RealtimeScheduling, ThreadsStartedAfterwardsRunOnOrdinaryScheduling) {
  RealtimeScheduling granted;
  int bench_policy = -1;
  int helper_policy = -1;
  std::thread bench_like([&] {
    granted = request_realtime_scheduling();
    bench_policy = sched_getscheduler(0) & ~SCHED_RESET_ON_FORK;
    std::thread helper([&] { helper_policy = sched_getscheduler(0); });
    helper.join();
  });
  bench_like.join();
  if (!granted.fifo) GTEST_SKIP() << "no real-time scheduling here: " << granted.message;
  EXPECT_EQ(bench_policy, SCHED_FIFO);
  EXPECT_EQ(helper_policy, SCHED_OTHER);
}

}  // namespace
}  // namespace wavebench::daemon
