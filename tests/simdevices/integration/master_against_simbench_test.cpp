// The project's CANopen master (drivers/canopen) against the simulated devices, in-process on
// one VirtualCanBus, with the bench on the real-time clock so the master's timeouts are real.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "../../support/simulated_devices_gear.hpp"
#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/cia406_encoder.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/sdo_client.hpp"
#include "wavebench/canopen/sync_producer.hpp"
#include "wavebench/canopen/torque_sensor.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"

namespace wavebench::simdevices {
namespace {

using namespace std::chrono_literals;

class MasterAgainstSimBench : public ::testing::Test {
 protected:
  void SetUp() override {
    SimulatedBenchConfig config = wavebench::testing::simulated_devices_config();
    config.clock = BenchClock::kRealTime;
    bus = std::make_unique<can::VirtualCanBus>(io);
    master = bus->endpoint("master");
    devices = bus->endpoint("simbench");
    bench = std::make_unique<SimulatedBench>(config, *devices);
    bench->start();
    drive_sdo = std::make_unique<canopen::SdoClient>(*master, 1);
    encoder_sdo = std::make_unique<canopen::SdoClient>(*master, 3);
    torque_sdo = std::make_unique<canopen::SdoClient>(*master, 4);
  }
  void TearDown() override {
    drive_sdo.reset();
    encoder_sdo.reset();
    torque_sdo.reset();
    bench.reset();
  }

  boost::asio::io_context io;
  std::unique_ptr<can::VirtualCanBus> bus;
  std::unique_ptr<can::VirtualCanEndpoint> master;
  std::unique_ptr<can::VirtualCanEndpoint> devices;
  std::unique_ptr<SimulatedBench> bench;
  std::unique_ptr<canopen::SdoClient> drive_sdo, encoder_sdo, torque_sdo;
};

TEST_F(MasterAgainstSimBench, IdentityAndDeviceNameBySegmentedUpload) {
  const auto name = drive_sdo->upload(0x1008, 0);
  EXPECT_EQ(std::string(name.begin(), name.end()), "WB-SIM servo drive");
  EXPECT_EQ(drive_sdo->read<std::uint32_t>(0x1000, 0), 0x00020192u);
  EXPECT_EQ(drive_sdo->read<std::uint8_t>(0x1018, 0), 4u);
  EXPECT_EQ(encoder_sdo->read<std::uint32_t>(0x1018, 2), 0x406u);
  std::error_code ec;
  drive_sdo->upload(0x2345, 0, ec);
  EXPECT_EQ(ec, canopen::make_error_code(canopen::SdoAbort::no_object));
}

TEST_F(MasterAgainstSimBench, EncoderConfigurationAndRemappedTpdoOnSync) {
  canopen::Cia406Encoder encoder(*encoder_sdo);
  encoder.read_configuration();
  EXPECT_TRUE(encoder.multi_turn());
  EXPECT_EQ(encoder.counts_per_turn(), 1u << 20);
  EXPECT_EQ(encoder.turns(), 2048u);

  canopen::PdoConfig pdo;
  pdo.cob_id = 0x183;
  pdo.transmission_type = 1;
  pdo.entries = {canopen::PdoEntry{0x6004, 0, 32}, canopen::PdoEntry{0x6503, 0, 16}};
  canopen::configure_pdo(*encoder_sdo, canopen::PdoDirection::transmit, 1, pdo);
  EXPECT_EQ(encoder_sdo->read<std::uint8_t>(0x1A00, 0), 2u);
  EXPECT_EQ(encoder_sdo->read<std::uint32_t>(0x1A00, 2), 0x65030010u);

  int encoder_frames = 0;
  int six_bytes = 0;
  auto sub = master->on_frame([&](const can::Frame& f) {
    if (f.id == 0x183) {
      ++encoder_frames;
      if (f.len == 6) ++six_bytes;
    }
  });
  canopen::NmtMaster nmt(*master);
  nmt.send(canopen::NmtCommand::start, 0);
  canopen::SyncProducer sync(*master, 1000us);
  sync.start();
  io.run_for(100ms);
  sync.stop();
  io.restart();
  io.poll();
  EXPECT_GT(encoder_frames, 0);
  EXPECT_EQ(encoder_frames, six_bytes);
  EXPECT_EQ(static_cast<std::uint64_t>(encoder_frames), sync.statistics().sent);
}

TEST_F(MasterAgainstSimBench, DriveEnablesMovesInProfilePositionAndRecoversFromFault) {
  canopen::Cia402Drive drive(*drive_sdo);
  drive.enable_operation();
  std::error_code ec;
  EXPECT_EQ(drive.state(ec), canopen::Cia402State::operation_enabled);
  drive.set_mode(canopen::OperationMode::profile_position);
  canopen::ProfileMove move;
  move.target = 2 * 131072;
  drive.move(move);
  drive.wait_target_reached(5000ms);
  EXPECT_NEAR(drive_sdo->read<std::int32_t>(0x6064, 0), move.target, 20);

  drive_sdo->write<std::uint16_t>(0x2F00, 0, 0x7121);
  EXPECT_EQ(drive.error_code(ec), 0x7121);
  drive.enable_operation();  // resets the fault on the way
  EXPECT_EQ(drive.state(ec), canopen::Cia402State::operation_enabled);
  EXPECT_EQ(drive.error_code(ec), 0u);
}

TEST_F(MasterAgainstSimBench, TorqueSensorReadsTheShaftTorque) {
  canopen::TorqueSensorConfig c;
  c.index = 0x6130;
  c.sub = 1;
  c.type = canopen::ValueType::i32;
  c.scale = 1e-3;
  canopen::TorqueSensor sensor(*torque_sdo, c);
  EXPECT_NEAR(sensor.read_torque(), 0.0, 0.2);  // at rest, no brake: noise only
}

}  // namespace
}  // namespace wavebench::simdevices
