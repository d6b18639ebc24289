// The cycle engine (cycle_engine.hpp) on the simulated clock with two fake CANopen devices on an
// in-process bus: every channel lands at the slot its device was bound to, a cycle closes as
// soon as its last frame arrives (the next SYNC follows at once), a missing device leaves its
// channel's flag clear and the cycle closes on the real-time timeout, and a duplicate frame is
// counted, never written twice. Also the heartbeat watch and the channel slots (pure parts).
#include "wavebench/bench/cycle_engine.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

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
  SimulatedSyncClock clock{*master_end, 1e-3, std::chrono::milliseconds(5),
                           std::chrono::milliseconds(100)};
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

// A TPDO of node `node` as a can::Frame (for the heartbeat watch's "any frame" rule).
can::Frame tpdo(canopen::NodeId node) {
  return value_frame(node, 0);
}

TEST(HeartbeatWatch, RealClockJudgesWallSilenceAndKeepsTheLargestProcessingGap) {
  HeartbeatWatch w;
  const std::vector<canopen::NodeId> nodes{1, 2};
  const auto t0 = HeartbeatWatch::Clock::now();
  w.arm(nodes, 0.0, 0.5, false, t0);
  w.seen(1, 0.1, t0 + std::chrono::milliseconds(100));
  w.seen(1, 0.2, t0 + std::chrono::milliseconds(200));
  w.seen(1, 0.45, t0 + std::chrono::milliseconds(450));
  w.seen(2, 0.4, t0 + std::chrono::milliseconds(400));
  EXPECT_FALSE(w.lost(0.9, t0 + std::chrono::milliseconds(900)));
  const auto lost = w.lost(0.91, t0 + std::chrono::milliseconds(910));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->node, 2);
  EXPECT_NEAR(lost->silent_s, 0.51, 1e-9);
  EXPECT_TRUE(w.missing(2, 0.91, t0 + std::chrono::milliseconds(910)));
  EXPECT_FALSE(w.missing(1, 0.91, t0 + std::chrono::milliseconds(910)));
  EXPECT_EQ(w.count(1), 3U);
  EXPECT_NEAR(w.largest_gap(1), 0.25, 1e-9);
  w.seen(9, 1.0, t0);  // not watched
  EXPECT_FALSE(w.watches(9));
  w.arm(nodes, 0.0, 0.0, false, t0);  // timeout 0: never judged
  EXPECT_FALSE(w.lost(100.0, t0 + std::chrono::seconds(100)));
}

TEST(HeartbeatWatch, SimulatedClockSlowerThanRealTimeDoesNotTripWhileTheNodeSendsFrames) {
  HeartbeatWatch w;
  const std::vector<canopen::NodeId> nodes{3};
  const auto t0 = HeartbeatWatch::Clock::now();
  w.arm(nodes, 0.0, 0.5, true, t0);
  w.seen(3, 0.0, t0);
  // A loaded machine: 2 s of wall time are 0.2 s of bench time; its PDOs keep coming.
  for (int ms = 10; ms <= 2000; ms += 10) {
    const auto wall = t0 + std::chrono::milliseconds(ms);
    w.frame(tpdo(3), wall);
    ASSERT_FALSE(w.lost(ms * 1e-4, wall)) << ms;
  }
}

TEST(HeartbeatWatch, SimulatedClockFasterThanRealTimeTripsWithinTheTimeoutOfWallTime) {
  HeartbeatWatch w;
  const std::vector<canopen::NodeId> nodes{3};
  const auto t0 = HeartbeatWatch::Clock::now();
  w.arm(nodes, 0.0, 0.5, true, t0);
  w.seen(3, 0.0, t0);
  // Bench time runs 10x real time; the heartbeat stopped, the PDOs go on.
  for (int ms = 10; ms <= 500; ms += 10) {
    const auto wall = t0 + std::chrono::milliseconds(ms);
    w.frame(tpdo(3), wall);
    ASSERT_FALSE(w.lost(ms * 1e-2, wall)) << ms;  // not yet 0.5 s of wall time
  }
  const auto lost = w.lost(5.01, t0 + std::chrono::milliseconds(501));
  ASSERT_TRUE(lost);
  EXPECT_NEAR(lost->silent_s, 0.501, 1e-9);  // the wall-clock silence, truthfully
}

TEST(HeartbeatWatch, SimulatedClockSilentBusTripsOnWallTimeThoughBenchTimeStandsStill) {
  HeartbeatWatch w;
  const std::vector<canopen::NodeId> nodes{1, 3};
  const auto t0 = HeartbeatWatch::Clock::now();
  w.arm(nodes, 1.0, 0.5, true, t0);
  w.seen(1, 1.0, t0);
  w.seen(3, 1.0, t0);
  w.frame(tpdo(1), t0 + std::chrono::milliseconds(50));
  // Nothing more: no SYNC completes, bench time stays at 1.0 s.
  EXPECT_FALSE(w.lost(1.0, t0 + std::chrono::milliseconds(500)));
  const auto lost = w.lost(1.0, t0 + std::chrono::milliseconds(551));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->node, 1);
  EXPECT_NEAR(lost->silent_s, 0.551, 1e-9);
  // The master's own frames (SDO requests, RPDOs) and SYNC say nothing of a node.
  HeartbeatWatch v;
  v.arm(nodes, 1.0, 0.5, true, t0);
  v.frame(can::Frame::make(0x601, {0x40, 0, 0x10, 0, 0, 0, 0, 0}),
          t0 + std::chrono::milliseconds(400));
  v.frame(can::Frame::make(0x201, {0, 0}), t0 + std::chrono::milliseconds(400));
  EXPECT_TRUE(v.lost(1.0, t0 + std::chrono::milliseconds(501)));
}

// A device slower than the SYNC rate: node 6 answers each SYNC only 30 ms later (the cycle
// timeout is 5 ms). The next SYNC waits for its late answer instead of queueing up behind it.
TEST(SimulatedSyncClock, WaitsForLateAnswersInsteadOfQueueingSyncsAndCountsTheWait) {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  auto master_end = bus.endpoint("master");
  auto devices_end = bus.endpoint("devices");
  canopen::Master master{*master_end, {}};
  SimulatedSyncClock clock{*master_end, 1e-3, std::chrono::milliseconds(5),
                           std::chrono::milliseconds(400)};
  CycleEngine engine{master, clock};
  FakeDevice a{5, "theta_out"};
  FakeDevice b{6, "extra_angle"};
  a.bind({slot::kThetaOut});
  b.bind({ChannelSlot::extra(0)});
  engine.attach({&a, &b}, {});
  Collector collector;
  engine.add_observer(collector);
  std::vector<std::string> events;  // "S" a SYNC seen by the devices, "B" node 6 answered
  boost::asio::steady_timer slow{io};
  std::int32_t k = 0;
  auto answer = devices_end->on_frame([&](const can::Frame& f) {
    if (f.id != 0x80) return;
    events.push_back("S");
    ++k;
    devices_end->send(value_frame(5, 1000 * k));
    slow.expires_after(std::chrono::milliseconds(30));
    slow.async_wait([&, value = 2000 * k](const boost::system::error_code& ec) {
      if (ec) return;
      events.push_back("B");
      devices_end->send(value_frame(6, value));
    });
  });
  engine.start(nullptr);
  while (collector.samples.size() < 5) io.run_one_for(std::chrono::milliseconds(50));
  engine.stop();
  ASSERT_GE(events.size(), 10U);
  // Every SYNC after the first follows the slow device's answer to the one before.
  for (std::size_t i = 0; i + 1 < events.size(); i += 2) {
    EXPECT_EQ(events[i], "S") << i;
    EXPECT_EQ(events[i + 1], "B") << i;
  }
  for (const auto& s : collector.samples) {
    EXPECT_TRUE(s.valid(storage::kThetaOutValid));
    EXPECT_TRUE(s.extra_arrived(0));
    EXPECT_DOUBLE_EQ(s.extra[0], 2 * s.theta_out_rad);
  }
  const auto stats = clock.statistics();
  EXPECT_GE(stats.cycles_waited_for_devices, 5U);
  EXPECT_GE(stats.cycles_timed_out, 5U);
  EXPECT_EQ(stats.cycles_given_up, 0U);
  EXPECT_GE(stats.longest_device_wait_s, 0.025);
  EXPECT_LT(stats.longest_device_wait_s, 0.4);
  EXPECT_EQ(engine.late_devices(), std::vector<std::string>{"fake (node 6)"});
}

TEST(SimulatedSyncClock, ADeviceThatNeverAnswersIsGivenUpOnceThenNotWaitedFor) {
  Rig rig;
  rig.b_answers = false;
  rig.engine.start(nullptr);
  rig.run_until_samples(20);
  rig.engine.stop();
  const auto stats = rig.clock.statistics();
  EXPECT_EQ(stats.cycles_given_up, 1U);
  EXPECT_EQ(stats.cycles_waited_for_devices, 0U);
  EXPECT_TRUE(rig.engine.late_devices().empty());  // not late: mute
  EXPECT_GE(stats.cycles_timed_out, 20U);
}

}  // namespace
}  // namespace wavebench::bench
