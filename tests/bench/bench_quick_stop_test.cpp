// The safety path never waits (issue #9, bench.md §7), on the in-process simulated bench with
// every frame on the bus captured. A trip raised while a segmented SDO upload is in flight puts
// the quick-stop RPDO (COB-ID 0x200 + drive node, data 02 00) on the bus within 2 SYNC periods,
// counted in SYNC frames (0x080) between the trip and that frame, not in wall-clock time. A
// drive that ignores the RPDO gets NMT stop (000# 02 node) after can.quick_stop_timeout, which
// switches its power stage off (abort connection option 0x6007 = 2, written by the bench).
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>

#include "bench_test_support.hpp"
#include "wavebench/bench/canopen_bench.hpp"
#include "wavebench/can/virtual_can_bus.hpp"

namespace wavebench::bench {
namespace {

using simdevices::Cia402State;
using testing::kRpm;
using testing::sim_config;
using testing::SimBench;

constexpr std::uint8_t kDrive = 1;
constexpr std::uint16_t kLongText = 0x2F10;  // manufacturer area, added by the test

using FramePredicate = std::function<bool(const can::Frame&)>;

bool is_sync(const can::Frame& f) {
  return f.id == 0x080;
}
bool is_quick_stop(const can::Frame& f) {
  return f.id == 0x200U + kDrive && f.len == 2 && f.data[0] == 0x02 && f.data[1] == 0x00;
}
bool is_nmt_stop_of_drive(const can::Frame& f) {
  return f.id == 0x000 && f.len == 2 && f.data[0] == 0x02 && f.data[1] == kDrive;
}
bool is_long_text_upload_request(const can::Frame& f) {
  return f.id == 0x600U + kDrive && f.len == 8 && f.data[0] == 0x40 &&
         f.data[1] == (kLongText & 0xFF) && f.data[2] == (kLongText >> 8);
}
bool is_drive_sdo_response(const can::Frame& f) {
  return f.id == 0x580U + kDrive;
}

std::size_t find_first(const std::vector<can::Frame>& log, std::size_t from,
                       const FramePredicate& match) {
  for (std::size_t i = from; i < log.size(); ++i)
    if (match(log[i])) return i;
  return log.size();
}
std::size_t find_last(const std::vector<can::Frame>& log, const FramePredicate& match) {
  for (std::size_t i = log.size(); i-- > 0;)
    if (match(log[i])) return i;
  return log.size();
}
std::size_t count(const std::vector<can::Frame>& log, std::size_t from, std::size_t to,
                  const FramePredicate& match) {
  std::size_t n = 0;
  for (std::size_t i = from; i < to && i < log.size(); ++i) n += match(log[i]) ? 1 : 0;
  return n;
}

// Connected, the drive enabled and turning, and the bus recording from here on.
can::VirtualCanBus& turn_and_record(SimBench& sim) {
  sim.bench->connect();
  sim.bench->run_input_velocity(100 * kRpm);
  sim.bench->wait_for(0.2);
  EXPECT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
  auto& bus = sim.access->virtual_bus();
  bus.clear_log();
  bus.record(true);
  return bus;
}

std::string trip_reason(SimBench& sim, const std::string& why) {
  sim.bench->request_stop(why);
  try {
    sim.bench->wait_for(10.0);
  } catch (const BenchAborted& e) {
    return e.what();
  }
  ADD_FAILURE() << "the bench did not trip";
  return {};
}

TEST(BenchQuickStop, TripDuringASegmentedUploadPutsTheQuickStopOnTheBusWithinTwoSyncs) {
  SimBench sim(sim_config());
  auto& bus = turn_and_record(sim);
  // A visible string long enough for its segmented upload (7 bytes a segment) to span many
  // SYNC periods: an SDO quick stop queued behind it would be that late.
  std::string text;
  while (text.size() < 700) text += "wavebench quick stop test text; ";
  sim.access->devices().drive().od().add_string(kLongText, 0, "long text (test)",
                                                simdevices::Access::kReadOnly, text);
  bool uploaded = false;
  std::error_code upload_error;
  std::vector<std::uint8_t> upload;
  sim.access->canopen().master().sdo(kDrive).async_upload(
      kLongText, 0, [&](std::error_code ec, std::vector<std::uint8_t> data) {
        uploaded = true;
        upload_error = ec;
        upload = std::move(data);
      });

  const auto trip_at = bus.log().size();
  const auto reason = trip_reason(sim, "trip during an SDO upload");
  EXPECT_EQ(reason, "operator stop: trip during an SDO upload");
  sim.bench->idle_for(0.5);  // the upload finishes beside the fault
  bus.record(false);
  const auto& log = bus.log();

  const auto quick_stop = find_first(log, trip_at, is_quick_stop);
  ASSERT_LT(quick_stop, log.size()) << "no quick-stop RPDO on the bus after the trip";
  const auto syncs = count(log, trip_at, quick_stop, is_sync);
  EXPECT_LE(syncs, 2U);
  // The upload was in flight around the quick stop: requested before it, answered after it,
  // over more than 2 SYNC periods, and it still completed intact.
  const auto upload_start = find_first(log, 0, is_long_text_upload_request);
  const auto upload_end = find_last(log, is_drive_sdo_response);
  ASSERT_LT(upload_start, quick_stop);
  ASSERT_LT(upload_end, log.size());
  EXPECT_GT(upload_end, quick_stop);
  EXPECT_GT(count(log, quick_stop, upload_end, is_sync), 2U);
  ASSERT_TRUE(uploaded);
  EXPECT_FALSE(upload_error) << upload_error.message();
  EXPECT_EQ(std::string(upload.begin(), upload.end()), text);

  // The drive took it: no NMT stop, quick stop active (0x605A = 6 keeps it there).
  EXPECT_EQ(count(log, 0, log.size(), is_nmt_stop_of_drive), 0U);
  EXPECT_EQ(sim.drive_state(), Cia402State::kQuickStopActive)
      << simdevices::to_string(sim.drive_state());
  EXPECT_FALSE(sim.brake_output_on());
  std::printf(
      "quick stop %zu SYNC(s) after the trip; the upload in flight went on for %zu SYNC(s) "
      "after it\n",
      syncs, count(log, quick_stop, upload_end, is_sync));
}

TEST(BenchQuickStop, ADriveIgnoringTheRpdoGetsNmtStopAfterTheTimeout) {
  // A stopped drive sends no PDOs: every cycle waits out its (short) timeout.
  SimBench sim(sim_config([](BenchConfig& c) { c.can.cycle_timeout_s = 0.002; }));
  auto& bus = turn_and_record(sim);
  auto& drive = sim.access->devices().drive();
  EXPECT_EQ(drive.od().get<std::int16_t>(0x6007, 0), 2);  // written by the bench at connect
  // The drive's RPDO1 disabled behind the bench's back (COB-ID bit 31): the quick stop is lost.
  drive.od().set<std::uint32_t>(0x1400, 1, 0x80000000U | (0x200U + kDrive));

  const auto trip_at = bus.log().size();
  const auto reason = trip_reason(sim, "drive ignores the quick stop");
  sim.bench->idle_for(0.01);  // the in-process bus delivers while the loop turns
  bus.record(false);
  const auto& log = bus.log();
  const auto quick_stop = find_first(log, trip_at, is_quick_stop);
  ASSERT_LT(quick_stop, log.size());
  EXPECT_LE(count(log, trip_at, quick_stop, is_sync), 2U);
  const auto nmt_stop = find_first(log, quick_stop, is_nmt_stop_of_drive);
  ASSERT_LT(nmt_stop, log.size()) << "no NMT stop after the ignored quick stop";
  // 50 ms of bench time at a 1 ms SYNC: the statusword had that many cycles to show it.
  const auto waited = count(log, quick_stop, nmt_stop, is_sync);
  EXPECT_GE(waited, 1U);
  EXPECT_LE(waited, 52U);
  EXPECT_NE(reason.find("operator stop: drive ignores the quick stop"), std::string::npos);
  EXPECT_NE(reason.find("did not show the quick stop within 50 ms"), std::string::npos) << reason;
  EXPECT_NE(reason.find("operation enabled"), std::string::npos) << reason;
  EXPECT_NE(reason.find("NMT stop sent to node 1"), std::string::npos) << reason;
  EXPECT_EQ(sim.bench->fault_reason(), reason);

  EXPECT_EQ(drive.nmt_state(), simdevices::NmtState::kStopped);
  EXPECT_EQ(sim.drive_state(), Cia402State::kSwitchOnDisabled)
      << simdevices::to_string(sim.drive_state());
  EXPECT_FALSE(sim.brake_output_on());
  std::printf("NMT stop %zu SYNC(s) after the unanswered quick stop\n", waited);

  // The reset starts the drive again; it stays off until motion needs it.
  sim.bench->clear_fault();
  EXPECT_EQ(sim.bench->state(), BenchLifecycle::kInactive);
  EXPECT_EQ(drive.nmt_state(), simdevices::NmtState::kOperational);
  EXPECT_EQ(sim.drive_state(), Cia402State::kSwitchOnDisabled);
  sim.bench->run_input_velocity(30 * kRpm);
  EXPECT_EQ(sim.drive_state(), Cia402State::kOperationEnabled);
}

}  // namespace
}  // namespace wavebench::bench
