#pragma once
// Conversion between engineering values and the 16-bit registers that carry them.

#include <cstdint>
#include <vector>

#include "wavebench/modbus/register_map.hpp"

namespace wavebench::modbus {

// Raw registers -> engineering value. `regs` must hold register_count(spec.type) words.
double decode_value(const RegisterSpec& spec, WordOrder order, const uint16_t* regs);

// Engineering value -> raw registers. Throws std::out_of_range naming the value if the raw
// value does not fit the register's type.
std::vector<uint16_t> encode_value(const RegisterSpec& spec, WordOrder order, double value);

// The 32-bit pattern split into two registers in the given byte order, and back.
void split_u32(uint32_t bits, WordOrder order, uint16_t* regs);
uint32_t join_u32(const uint16_t* regs, WordOrder order);

}  // namespace wavebench::modbus
