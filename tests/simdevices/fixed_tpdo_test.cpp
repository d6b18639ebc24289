// Simulated devices whose TPDO mapping cannot be written (issue 20): `fixed_tpdo_mapping` makes
// a TPDO's communication and mapping parameters read-only (SDO write: abort 06010002, byte
// exact) with the configured layout, sent on every SYNC; the RPDOs stay writable.
#include <gtest/gtest.h>

#include "../support/simulated_devices_gear.hpp"
#include "bench_fixture.hpp"
#include "wavebench/simdevices/simulated_bench_config.hpp"

namespace wavebench::simdevices::testing {
namespace {

class FixedTpdoTest : public BenchFixture {
 protected:
  FixedTpdoTest() {
    config = parse_simulated_bench_config(R"(
simbench:
  drive:
    fixed_tpdo_mapping: {tpdo1: ["0x6064:0/32", "0x6041:0/16"], tpdo2: ["0x606C:0/32"]}
)",
                                          config);
  }
};

TEST_F(FixedTpdoTest, WritesToTheTpdoParametersAreRefusedReadOnly) {
  // 0x1A00:0 = 0 (the remap's first mapping write): abort 06010002.
  auto r = exchange(0x601, {0x2F, 0x00, 0x1A, 0x00, 0x00, 0, 0, 0});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], frame(0x581, {0x80, 0x00, 0x1A, 0x00, 0x02, 0x00, 0x01, 0x06}));
  // 0x1800:1 = COB-ID invalid (the remap's first write), 0x1801:2 = 254, 0x1A01:1.
  r = exchange(0x601, {0x23, 0x00, 0x18, 0x01, 0x81, 0x01, 0x00, 0x80});
  EXPECT_EQ(r.at(0), frame(0x581, {0x80, 0x00, 0x18, 0x01, 0x02, 0x00, 0x01, 0x06}));
  r = exchange(0x601, {0x2F, 0x01, 0x18, 0x02, 0xFE, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x581, {0x80, 0x01, 0x18, 0x02, 0x02, 0x00, 0x01, 0x06}));
  r = exchange(0x601, {0x23, 0x01, 0x1A, 0x01, 0x20, 0x00, 0x64, 0x60});
  EXPECT_EQ(r.at(0), frame(0x581, {0x80, 0x01, 0x1A, 0x01, 0x02, 0x00, 0x01, 0x06}));
  // Readable: the layout as configured, COB-ID 0x181 valid, type 1.
  r = exchange(0x601, {0x40, 0x00, 0x1A, 0x01, 0, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x581, {0x43, 0x00, 0x1A, 0x01, 0x20, 0x00, 0x64, 0x60}));
  r = exchange(0x601, {0x40, 0x00, 0x18, 0x01, 0, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x581, {0x43, 0x00, 0x18, 0x01, 0x81, 0x01, 0x00, 0x00}));
  r = exchange(0x601, {0x40, 0x01, 0x1A, 0x00, 0, 0, 0, 0});
  EXPECT_EQ(r.at(0), frame(0x581, {0x4F, 0x01, 0x1A, 0x00, 0x01, 0, 0, 0}));
  // The RPDO stays writable (the bench's quick stop maps RPDO1).
  r = exchange(0x601, {0x23, 0x00, 0x14, 0x01, 0x01, 0x02, 0x00, 0x80});
  EXPECT_EQ(r.at(0), frame(0x581, {0x60, 0x00, 0x14, 0x01, 0, 0, 0, 0}));
}

TEST_F(FixedTpdoTest, TheFixedLayoutIsSentOnEverySync) {
  bench->drive().od().set<std::int32_t>(0x6064, 0, 0x12345678);
  send(0x000, {0x01, 0x01});
  received.clear();
  send(0x080, {});
  const auto tpdo1 = frames_with_id(0x181);
  ASSERT_EQ(tpdo1.size(), 1u);
  EXPECT_EQ(tpdo1[0].len, 6);
  EXPECT_EQ(tpdo1[0].data[3], 0x12);  // position first, then the statusword
  EXPECT_EQ(frames_with_id(0x281).size(), 1u);
  EXPECT_EQ(frames_with_id(0x281)[0].len, 4);
}

void expect_message(const std::string& yaml, const std::string& fragment) {
  try {
    parse_simulated_bench_config(yaml);
    FAIL() << "accepted: " << yaml;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(FixedTpdoConfig, ReadsLayoutsAndRefusesBadOnesNamingKeyValueAndExpectation) {
  const auto c = parse_simulated_bench_config(
      "simbench: {encoder: {fixed_tpdo_mapping: {tpdo1: [\"0x6004:0/32\"], tpdo3: []}}}");
  ASSERT_EQ(c.encoder.fixed_tpdos.size(), 2u);
  EXPECT_EQ(c.encoder.fixed_tpdos[0].number, 1);
  EXPECT_EQ(c.encoder.fixed_tpdos[0].mapping.at(0).encoded(), 0x60040020u);
  EXPECT_EQ(c.encoder.fixed_tpdos[1].number, 3);
  EXPECT_TRUE(c.encoder.fixed_tpdos[1].mapping.empty());
  expect_message("simbench: {drive: {fixed_tpdo_mapping: {tpdo1: [\"0x6064/32\"]}}}",
                 "simbench.drive.fixed_tpdo_mapping.tpdo1[0]: got '0x6064/32', expected "
                 "INDEX:SUB/BITS like \"0x6064:0/32\"");
  expect_message("simbench: {drive: {fixed_tpdo_mapping: {tpdo1: [\"0x6064:0/12\"]}}}",
                 "tpdo1[0]: got '0x6064:0/12'");
  expect_message("simbench: {drive: {fixed_tpdo_mapping: {tpdo5: []}}}", "tpdo5");
  expect_message(
      "simbench: {drive: {fixed_tpdo_mapping: {tpdo1: [\"0x6064:0/32\", \"0x606C:0/32\", "
      "\"0x6041:0/16\"]}}}",
      "at most 8 objects of together at most 64 bits");
}

TEST(FixedTpdoConfig, AnObjectTheDeviceLacksIsRefusedWhenBuilt) {
  auto c = parse_simulated_bench_config(
      "simbench: {drive: {absent_objects: [\"0x60F4\"], fixed_tpdo_mapping: {tpdo2: "
      "[\"0x60F4:0/32\"]}}}");
  c.gear = wavebench::testing::simulated_devices_gear();
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint("simbench");
  try {
    SimulatedBench bench(c, *ep);
    FAIL() << "built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fixed TPDO2: object 0x60F4:0 is not in the node's "
                                         "dictionary"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wavebench::simdevices::testing
