// The cycle engine (cycle_engine.hpp) on the simulated clock with two fake CANopen devices on an
// in-process bus: every channel lands at the slot its device was bound to, a cycle closes as
// soon as its last frame arrives (the next SYNC follows at once), a missing device leaves its
// channel's flag clear and the cycle closes on the real-time timeout, and a duplicate frame is
// counted, never written twice. Also the heartbeat watch and the channel slots (pure parts).
#include "wavebench/bench/cycle_engine.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "wavebench/bench/bench.hpp"
#include "wavebench/bench/heartbeat_watch.hpp"
#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/canopen/sync_producer.hpp"

namespace wavebench::bench {
namespace {

// One TPDO with one INTEGER32 in milli-units: the channel's value is raw / 1000.
class FakeDevice final : public CanopenDevice {
 public:
  FakeDevice(canopen::NodeId node, std::string channel)
      : CanopenDevice("fake", node), channel_(std::move(channel)) {}
  std::vector<storage::ChannelInfo> channels() const override { return {{channel_, "rad"}}; }
  std::vector<canopen::UsedObject> used_objects() const override { return {}; }
  void configure(canopen::SdoClient&) override {}
  std::vector<canopen::PdoConfig> tpdos() const override {
    return {{canopen::tpdo_cob_id(1, node()), 1, 0, {{0x6004, 0, 32}}}};
  }
  void on_sync(std::uint64_t index) noexcept override { last_sync = index; }
  bool on_pdo(std::size_t i, const can::Frame& f, CycleRecord& r) noexcept override {
    if (i != 0 || f.len < 4) return false;
    const auto raw = static_cast<std::int32_t>(f.data[0] | f.data[1] << 8 | f.data[2] << 16 |
                                               static_cast<std::uint32_t>(f.data[3]) << 24);
    put(r, 0, raw / 1000.0);
    return true;
  }
  std::uint64_t last_sync = 0;

 private:
  std::string channel_;
};

can::Frame value_frame(canopen::NodeId node, std::int32_t milli) {
  can::Frame f;
  f.id = canopen::tpdo_cob_id(1, node);
  f.len = 4;
  for (int b = 0; b < 4; ++b) f.data[b] = static_cast<std::uint8_t>(milli >> (8 * b));
  return f;
}

struct Collector final : SampleObserver {
  std::vector<storage::SyncSample> samples;
  void on_sample(const storage::SyncSample& s) noexcept override { samples.push_back(s); }
};

struct Rig {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master_end = bus.endpoint("master");
  std::unique_ptr<can::VirtualCanEndpoint> devices_end = bus.endpoint("devices");
  canopen::Master master{*master_end, {}};
  SimulatedSyncClock clock{*master_end, 1e-3, std::chrono::milliseconds(5)};
  CycleEngine engine{master, clock};
  FakeDevice a{5, "theta_out"};
  FakeDevice b{6, "extra_angle"};
  Collector collector;
  can::CanBus::Subscription answer;
  bool b_answers = true;
  bool a_twice = false;
  std::int32_t k = 0;

  Rig() {
    a.bind({slot::kThetaOut});
    b.bind({ChannelSlot::extra(0)});
    engine.attach({&a, &b}, {});
    engine.add_observer(collector);
    // The devices answer every SYNC with their TPDO, like synchronous nodes.
    answer = devices_end->on_frame([this](const can::Frame& f) {
      if (f.id != 0x80) return;
      ++k;
      devices_end->send(value_frame(5, 1000 * k));
      if (a_twice) devices_end->send(value_frame(5, -1));
      if (b_answers) devices_end->send(value_frame(6, 2000 * k));
    });
  }
  void run_until_samples(std::size_t n) {
    while (collector.samples.size() < n) io.run_one_for(std::chrono::milliseconds(50));
  }
};

TEST(CycleEngine, EveryChannelLandsAtItsSlotAndCompleteCyclesPaceTheSimulatedClock) {
  Rig rig;
  rig.engine.start(nullptr);
  rig.run_until_samples(50);
  rig.engine.stop();
  const auto& s = rig.collector.samples;
  for (std::size_t i = 0; i < 50; ++i) {
    ASSERT_TRUE(s[i].valid(storage::kThetaOutValid)) << i;
    EXPECT_FALSE(s[i].valid(storage::kThetaInValid)) << i;  // no device bound there
    ASSERT_TRUE(s[i].extra_arrived(0)) << i;
    EXPECT_DOUBLE_EQ(s[i].extra[0], 2 * s[i].theta_out_rad) << i;
    EXPECT_DOUBLE_EQ(s[i].theta_out_rad, static_cast<double>(i + 1)) << i;
    // Bench time is SYNC index × period, one SYNC per complete cycle.
    EXPECT_EQ(s[i].receive_time_ns, static_cast<std::int64_t>(i + 1) * 1000000) << i;
  }
  EXPECT_EQ(rig.engine.statistics().late_frames, 0U);
  EXPECT_EQ(rig.clock.statistics().cycles_timed_out, 0U);
  EXPECT_GE(rig.a.last_sync, 50U);
}

TEST(CycleEngine, AMissingDeviceLeavesItsFlagClearAndTheCycleClosesOnTheTimeout) {
  Rig rig;
  rig.b_answers = false;
  rig.engine.start(nullptr);
  rig.run_until_samples(5);
  rig.engine.stop();
  for (const auto& s : rig.collector.samples) {
    EXPECT_TRUE(s.valid(storage::kThetaOutValid));
    EXPECT_FALSE(s.extra_arrived(0));
  }
  EXPECT_GE(rig.clock.statistics().cycles_timed_out, 5U);
  EXPECT_GE(rig.engine.statistics().incomplete_samples, 5U);
}

TEST(CycleEngine, ADuplicateFrameIsCountedAndNotWritten) {
  Rig rig;
  rig.a_twice = true;
  rig.b_answers = false;  // keeps the cycle open so the duplicate arrives inside it
  rig.engine.start(nullptr);
  rig.run_until_samples(3);
  rig.engine.stop();
  for (const auto& s : rig.collector.samples) EXPECT_GT(s.theta_out_rad, 0);
  EXPECT_GE(rig.engine.statistics().late_frames, 3U);
}

TEST(CycleRecord, SlotsFollowTheCoreChannelTableThenTheExtras) {
  CycleRecord r;
  r.set(slot::kThetaIn, 1);
  r.set(slot::kBrakeTorque, 6);
  r.set(ChannelSlot::extra(7), 8);
  r.set(ChannelSlot::extra(8), 9);  // beyond the table: ignored
  EXPECT_EQ(r.sample.theta_in_rad, 1);
  EXPECT_EQ(r.sample.brake_torque_nm, 6);
  EXPECT_EQ(r.sample.flags, storage::kThetaInValid | storage::kBrakeTorqueValid);
  EXPECT_EQ(r.sample.extra[7], 8);
  EXPECT_EQ(r.sample.extra_valid, 1U << 7);
  const auto core = storage::core_channels();
  EXPECT_EQ(core[slot::kThetaOut.index].name, "theta_out");
  EXPECT_EQ(core[slot::kInputSpeed.index].name, "input_speed");
  EXPECT_EQ(core[slot::kTorque.index].name, "torque");
  EXPECT_EQ(core[slot::kBrakeCurrent.index].name, "brake_current");
}

TEST(HeartbeatWatch, JudgesSilenceInBenchTimeAndKeepsTheLargestProcessingGap) {
  HeartbeatWatch w;
  const std::vector<canopen::NodeId> nodes{1, 2};
  w.arm(nodes, 0.0, 0.5);
  const auto t0 = HeartbeatWatch::Clock::now();
  w.seen(1, 0.1, t0);
  w.seen(1, 0.2, t0 + std::chrono::milliseconds(100));
  w.seen(1, 0.45, t0 + std::chrono::milliseconds(350));
  w.seen(2, 0.4, t0);
  EXPECT_FALSE(w.lost(0.5));
  EXPECT_FALSE(w.lost(0.9));
  const auto lost = w.lost(0.91);
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->node, 2);
  EXPECT_NEAR(lost->silent_s, 0.51, 1e-12);
  EXPECT_TRUE(w.missing(2, 0.91));
  EXPECT_FALSE(w.missing(1, 0.91));
  EXPECT_EQ(w.count(1), 3U);
  EXPECT_NEAR(w.largest_gap(1), 0.25, 1e-9);
  w.seen(9, 1.0, t0);  // not watched
  EXPECT_FALSE(w.watches(9));
  w.arm(nodes, 0.0, 0.0);  // timeout 0: never judged
  EXPECT_FALSE(w.lost(100.0));
}

}  // namespace
}  // namespace wavebench::bench
