#include "wavebench/modbus/register_codec.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace wavebench::modbus {
namespace {

// 1.5f = 0x3FC00000, 123.456f = 0x42F6E979: bytes A B C D.
TEST(RegisterCodec, Float32WordOrders) {
  const RegisterSpec spec{RegisterTable::holding, 0, DataType::float32};
  struct Case {
    WordOrder order;
    uint16_t r0, r1;
  };
  for (const Case c :
       {Case{WordOrder::abcd, 0x42F6, 0xE979}, Case{WordOrder::cdab, 0xE979, 0x42F6},
        Case{WordOrder::badc, 0xF642, 0x79E9}, Case{WordOrder::dcba, 0x79E9, 0xF642}}) {
    const auto regs = encode_value(spec, c.order, 123.456);
    ASSERT_EQ(regs.size(), 2u);
    EXPECT_EQ(regs[0], c.r0) << to_string(c.order);
    EXPECT_EQ(regs[1], c.r1) << to_string(c.order);
    EXPECT_FLOAT_EQ(static_cast<float>(decode_value(spec, c.order, regs.data())), 123.456f);
  }
  const uint16_t one_and_half[] = {0x3FC0, 0x0000};
  EXPECT_DOUBLE_EQ(decode_value(spec, WordOrder::abcd, one_and_half), 1.5);
}

TEST(RegisterCodec, ScaledIntegers) {
  const RegisterSpec tenths{RegisterTable::input, 5, DataType::int16, 0.1, 0.0};
  const auto regs = encode_value(tenths, WordOrder::abcd, -12.3);
  EXPECT_EQ(regs[0], static_cast<uint16_t>(-123));
  EXPECT_NEAR(decode_value(tenths, WordOrder::abcd, regs.data()), -12.3, 1e-12);

  const RegisterSpec offset{RegisterTable::input, 5, DataType::uint16, 0.5, -40.0};
  const uint16_t raw[] = {200};
  EXPECT_DOUBLE_EQ(decode_value(offset, WordOrder::abcd, raw), 60.0);

  const RegisterSpec u32{RegisterTable::holding, 0, DataType::uint32};
  const auto w = encode_value(u32, WordOrder::cdab, 0x12345678);
  EXPECT_EQ(w[0], 0x5678);
  EXPECT_EQ(w[1], 0x1234);
  const RegisterSpec i32{RegisterTable::holding, 0, DataType::int32};
  const auto n = encode_value(i32, WordOrder::abcd, -2);
  EXPECT_EQ(n[0], 0xFFFF);
  EXPECT_EQ(n[1], 0xFFFE);
  EXPECT_DOUBLE_EQ(decode_value(i32, WordOrder::abcd, n.data()), -2.0);
}

TEST(RegisterCodec, OutOfRangeIsRejected) {
  const RegisterSpec u16{RegisterTable::holding, 1, DataType::uint16};
  EXPECT_THROW(encode_value(u16, WordOrder::abcd, 65536.0), std::out_of_range);
  EXPECT_THROW(encode_value(u16, WordOrder::abcd, -1.0), std::out_of_range);
  EXPECT_EQ(encode_value(u16, WordOrder::abcd, 65535.0)[0], 65535);
  const RegisterSpec f{RegisterTable::holding, 1, DataType::float32};
  EXPECT_THROW(encode_value(f, WordOrder::abcd, std::numeric_limits<double>::infinity()),
               std::out_of_range);
}

}  // namespace
}  // namespace wavebench::modbus

#include "wavebench/modbus/brake_status.hpp"

namespace wavebench::modbus {
namespace {

TEST(BrakeStatus, DecodesConfiguredBitsAndNamesAlarms) {
  BrakeRegisterMap map;
  const auto s = decode_status(0b101110, map.status_bits);
  EXPECT_FALSE(s.output_on);
  EXPECT_TRUE(s.alarm);
  EXPECT_TRUE(s.over_temperature);
  EXPECT_TRUE(s.watchdog_tripped);
  EXPECT_FALSE(s.coil_open);
  EXPECT_TRUE(s.at_setpoint);
  EXPECT_EQ(describe_alarms(s, 1, map),
            "alarm 1: coil over-temperature; over-temperature; "
            "watchdog tripped");
  EXPECT_EQ(describe_alarms(decode_status(0, map.status_bits), 0, map), "no alarm");
  EXPECT_EQ(describe_alarms(decode_status(0b10, map.status_bits), 77, map),
            "alarm 77: unknown alarm code");
  // A controller with other bit positions.
  map.status_bits.output_on = 8;
  map.status_bits.alarm = 15;
  const auto t = decode_status(0x8100, map.status_bits);
  EXPECT_TRUE(t.output_on);
  EXPECT_TRUE(t.alarm);
  EXPECT_FALSE(t.over_temperature);
}

}  // namespace
}  // namespace wavebench::modbus
