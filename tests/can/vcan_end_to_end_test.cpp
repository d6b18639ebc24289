// The whole CANopen path on a real vcan0: the simulated bench (drive, encoder, torque sensor) on
// its own socket, the master on another; PDOs configured by SDO, SYNC at 1 kHz, the drive
// enabled via CiA 402, a PP move and a PV run, synchronous samples; candump records the same
// traffic as a monitoring socket.
#include <gtest/gtest.h>

#include <map>

#include "../support/simulated_devices_gear.hpp"
#include "vcan_support.hpp"
#include "wavebench/can/socket_can_bus.hpp"
#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/heartbeat_consumer.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/sync_producer.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::canopen {
namespace {

using namespace std::chrono_literals;
using testing::kVcan;
using testing::run_until;

TEST(VcanEndToEnd, MasterRunsTheSimulatedBench) {
  WAVEBENCH_REQUIRE_VCAN();
  boost::asio::io_context io;
  can::SocketCanBus monitor(io, kVcan);
  std::vector<std::string> seen;
  auto record = monitor.on_frame([&](const can::Frame& f) { seen.push_back(can::to_string(f)); });

  const int receivers = testing::registered_receivers();
  testing::ChildProcess candump({"candump", "-L", kVcan}, "/tmp/wavebench_e2e_candump_" +
                                                              std::to_string(::getpid()) + ".log");
  ASSERT_TRUE(run_until(
      io, [&] { return testing::registered_receivers() > receivers || candump.exited(); }));
  ASSERT_FALSE(candump.exited()) << candump.output();

  can::SocketCanBus master(io, kVcan);
  can::SocketCanBus devices(io, kVcan);
  simdevices::SimulatedBenchConfig config = wavebench::testing::simulated_devices_config();
  config.clock = simdevices::BenchClock::kSyncDriven;
  simdevices::SimulatedBench bench(config, devices);
  bench.start();

  SdoClient drive_sdo(master, 1, 10s);
  SdoClient encoder_sdo(master, 3, 10s);
  SdoClient torque_sdo(master, 4, 10s);
  EXPECT_EQ(drive_sdo.read<std::uint32_t>(0x1000, 0) & 0xFFFFU, 0x0192U);  // CiA 402
  Cia406Encoder encoder(encoder_sdo);
  encoder.read_configuration();
  EXPECT_TRUE(encoder.multi_turn());

  // Synchronous TPDOs on every SYNC: drive statusword + position, encoder position, torque.
  configure_pdo(drive_sdo, PdoDirection::transmit, 1,
                PdoConfig{tpdo_cob_id(1, 1), 1, 0, {{0x6041, 0, 16}, {0x6064, 0, 32}}});
  configure_pdo(encoder_sdo, PdoDirection::transmit, 1,
                PdoConfig{tpdo_cob_id(1, 3), 1, 0, {{0x6004, 0, 32}}});
  TorqueSensorConfig torque_config;
  torque_config.index = 0x6130;
  torque_config.sub = 1;
  torque_config.type = ValueType::i32;
  torque_config.scale = 1e-3;
  TorqueSensor torque(torque_sdo, torque_config);
  configure_pdo(torque_sdo, PdoDirection::transmit, 1,
                PdoConfig{tpdo_cob_id(1, 4), 1, 0, {PdoEntry::decode(torque.mapping_entry())}});
  // Heartbeats from every node, watched by the master.
  int lost = 0;
  std::vector<std::unique_ptr<HeartbeatConsumer>> consumers;
  for (NodeId n : {1, 3, 4}) {
    SdoClient(master, n, 10s).write<std::uint16_t>(0x1017, 0, 100);
    consumers.push_back(std::make_unique<HeartbeatConsumer>(
        master, n, 60s,
        HeartbeatConsumer::Hooks{nullptr, [&](NodeId) noexcept { ++lost; }, nullptr}));
  }

  // Samples: the TPDOs that follow each SYNC.
  const PdoLayout drive_layout({{0x6041, 0, 16}, {0x6064, 0, 32}});
  struct Sample {
    std::optional<std::int64_t> drive_position, encoder_raw;
    std::optional<double> torque_nm;
  };
  std::vector<Sample> samples;
  auto sampler = master.on_frame([&](const can::Frame& f) {
    if (samples.empty()) return;  // before the first SYNC
    if (f.id == 0x181 && drive_layout.fits(f))
      samples.back().drive_position = drive_layout.signed_value(f, 1);
    if (f.id == 0x183 && f.len == 4)
      samples.back().encoder_raw =
          f.data[0] | f.data[1] << 8 | f.data[2] << 16 | std::int64_t{f.data[3]} << 24;
    if (f.id == 0x184) samples.back().torque_nm = torque.torque_from(f.payload());
  });
  // SYNC from the master's own socket is not looped back to it: count what it sends instead.
  SyncProducer sync(master, 1000us);
  sync.on_tick([&](const SyncProducer::Tick&) noexcept { samples.emplace_back(); });

  NmtMaster(master).send(NmtCommand::start, 0);
  sync.start();

  Cia402Options options;
  options.state_timeout = 60s;
  Cia402Drive drive(drive_sdo, options);
  drive.set_mode(OperationMode::profile_position);
  drive.enable_operation();
  ProfileMove move;
  move.target = 131072;  // one motor turn
  drive.move(move);
  drive.wait_target_reached(120s);
  EXPECT_NEAR(drive_sdo.read<std::int32_t>(0x6064, 0), move.target, 50);

  drive.set_mode(OperationMode::profile_velocity);
  drive.set_target_velocity(131072);  // one turn per second
  const auto start_position = drive_sdo.read<std::int32_t>(0x6064, 0);
  ASSERT_TRUE(run_until(io, [&] {
    return drive_sdo.read<std::int32_t>(0x6064, 0) > start_position + 13107;  // a tenth of a turn
  }));
  drive.set_target_velocity(0);
  drive.go_to(Cia402State::switch_on_disabled);
  sync.stop();

  // An end marker after everything: both recorders must have it.
  master.send(can::Frame::make(0x1FFFFFFF, {0xE2, 0xE0}));
  const std::string marker = "1FFFFFFF#E2E0";
  ASSERT_TRUE(run_until(io, [&] { return !seen.empty() && seen.back() == marker; }));
  ASSERT_TRUE(run_until(io, [&] { return candump.output().find(marker) != std::string::npos; }));
  candump.stop(SIGINT);

  // candump and our monitoring socket saw the same frames in the same order.
  const auto dumped = testing::candump_frames(candump.output());
  ASSERT_EQ(dumped.size(), seen.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    ASSERT_EQ(dumped[i], std::string(kVcan) + " " + seen[i]) << "frame " << i;
  }

  // Samples: every one that is complete has all three values; a move happened in them.
  std::size_t complete = 0;
  std::int64_t min_pos = INT64_MAX, max_pos = INT64_MIN;
  for (const auto& s : samples) {
    if (s.drive_position && s.encoder_raw && s.torque_nm) ++complete;
    if (s.drive_position) {
      min_pos = std::min(min_pos, *s.drive_position);
      max_pos = std::max(max_pos, *s.drive_position);
    }
  }
  EXPECT_GT(complete, 0U);
  EXPECT_GE(max_pos - min_pos, 131072 - 50);
  EXPECT_EQ(lost, 0);
  EXPECT_GT(sync.statistics().sent, 0U);
}

}  // namespace
}  // namespace wavebench::canopen
