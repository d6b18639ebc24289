// Node guarding on the simulated devices (byte-exact frames): a remote frame on 0x700 + id is
// answered with the NMT state and a toggle that starts at 0 after boot-up and alternates; a
// device configured without a heartbeat producer has no 0x1017 but 0x100C/0x100D; a silent
// node sends nothing; the simbench key `heartbeat_producer` is read strictly.
#include <gtest/gtest.h>

#include "bench_fixture.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"

namespace wavebench::simdevices::testing {
namespace {

can::Frame remote(std::uint32_t id) {
  can::Frame f;
  f.id = id;
  f.rtr = true;
  f.len = 1;
  return f;
}

class NodeGuardingTest : public BenchFixture {
 protected:
  NodeGuardingTest() { config.drive.identity.heartbeat_producer = false; }
  std::vector<can::Frame> ask(std::uint32_t id) {
    received.clear();
    master->send(remote(id));
    io.poll();
    io.restart();
    return received;
  }
};

TEST_F(NodeGuardingTest, RemoteFrameIsAnsweredWithStateAndAlternatingToggle) {
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0x7F})});
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0xFF})});
  send(0x000, {0x01, 0x01});  // operational
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0x05})});
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0x85})});
  send(0x000, {0x02, 0x01});  // stopped: error control still answers
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0x04})});
  // Reset communication: boot-up, then the toggle starts at 0 again.
  const auto boot = exchange(0x000, {0x82, 0x01});
  ASSERT_EQ(boot.size(), 1U);
  EXPECT_EQ(boot[0], frame(0x701, {0x00}));
  EXPECT_EQ(ask(0x701), std::vector<can::Frame>{frame(0x701, {0x7F})});
  // A node with a heartbeat producer answers node guarding too (CiA 301 allows either).
  EXPECT_EQ(ask(0x703), std::vector<can::Frame>{frame(0x703, {0x7F})});
  EXPECT_TRUE(ask(0x702).empty());  // nobody
}

TEST_F(NodeGuardingTest, WithoutAHeartbeatProducerThereIsNo1017But100CAnd100D) {
  // SDO upload of 0x1017: abort 0x06020000 (object does not exist).
  EXPECT_EQ(
      exchange(0x601, {0x40, 0x17, 0x10, 0x00, 0, 0, 0, 0}),
      std::vector<can::Frame>{frame(0x581, {0x80, 0x17, 0x10, 0x00, 0x00, 0x00, 0x02, 0x06})});
  // Guard time 100 ms and life time factor 3 are written.
  EXPECT_EQ(exchange(0x601, {0x2B, 0x0C, 0x10, 0x00, 0x64, 0x00, 0, 0}),
            std::vector<can::Frame>{frame(0x581, {0x60, 0x0C, 0x10, 0x00, 0, 0, 0, 0})});
  EXPECT_EQ(exchange(0x601, {0x2F, 0x0D, 0x10, 0x00, 0x03, 0, 0, 0}),
            std::vector<can::Frame>{frame(0x581, {0x60, 0x0D, 0x10, 0x00, 0, 0, 0, 0})});
  EXPECT_EQ(bench->drive().od().get<std::uint16_t>(0x100C, 0), 100U);
  // No heartbeat whatever the time.
  received.clear();
  advance(2.0);
  EXPECT_TRUE(frames_with_id(0x701).empty());
  // The encoder keeps its 0x1017.
  EXPECT_NE(bench->encoder().od().find(0x1017, 0), nullptr);
}

TEST_F(NodeGuardingTest, ASilentBenchSendsNothing) {
  send(0x000, {0x01, 0x00});
  bench->set_silent(true);
  EXPECT_TRUE(ask(0x701).empty());
  EXPECT_TRUE(exchange(0x080, {}).empty());
  EXPECT_TRUE(exchange(0x601, {0x40, 0x00, 0x10, 0x00, 0, 0, 0, 0}).empty());
  bench->set_silent(false);
  EXPECT_EQ(exchange(0x080, {}).size(), 4U);
}

TEST(SimulatedBenchConfigNodeGuarding, HeartbeatProducerKeyIsABoolean) {
  const auto c = parse_simulated_bench_config(
      "simbench: {drive: {heartbeat_producer: false}, encoder: {heartbeat_producer: false}, "
      "torque_sensor: {heartbeat_producer: true}}");
  EXPECT_FALSE(c.drive.identity.heartbeat_producer);
  EXPECT_FALSE(c.encoder.identity.heartbeat_producer);
  EXPECT_TRUE(c.torque_sensor.identity.heartbeat_producer);
  EXPECT_TRUE(parse_simulated_bench_config("simbench: {}").drive.identity.heartbeat_producer);
  try {
    parse_simulated_bench_config("simbench: {drive: {heartbeat_producer: maybe}}");
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "simbench.drive.heartbeat_producer: got 'maybe', expected true or false"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wavebench::simdevices::testing
