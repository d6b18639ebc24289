#pragma once
// SDO abort codes (CiA 301 §7.2.4.3.17) as std::error_code values of their own category, so
// every SDO call can report "06020000 object does not exist" in both its throwing and its
// error_code form.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <system_error>

namespace wavebench::canopen {

enum class SdoAbort : std::uint32_t {
  toggle_bit = 0x05030000,
  timeout = 0x05040000,
  invalid_command = 0x05040001,
  invalid_block_size = 0x05040002,
  invalid_sequence = 0x05040003,
  crc_error = 0x05040004,
  out_of_memory = 0x05040005,
  unsupported_access = 0x06010000,
  write_only = 0x06010001,
  read_only = 0x06010002,
  no_object = 0x06020000,
  not_mappable = 0x06040041,
  pdo_too_long = 0x06040042,
  parameter_incompatible = 0x06040043,
  device_incompatible = 0x06040047,
  hardware_error = 0x06060000,
  length_mismatch = 0x06070010,
  length_too_high = 0x06070012,
  length_too_low = 0x06070013,
  no_sub_index = 0x06090011,
  invalid_value = 0x06090030,
  value_too_high = 0x06090031,
  value_too_low = 0x06090032,
  max_below_min = 0x06090036,
  no_resource = 0x060A0023,
  general = 0x08000000,
  data_transfer = 0x08000020,
  local_control = 0x08000021,
  device_state = 0x08000022,
  no_dictionary = 0x08000023,
  no_data = 0x08000024,
};

const std::error_category& sdo_category() noexcept;
std::error_code make_error_code(SdoAbort abort) noexcept;
// "object does not exist in the object dictionary" for 0x06020000; unknown codes say so.
std::string abort_text(std::uint32_t code);
// The abort code carried by an error_code of sdo_category (general error otherwise).
std::uint32_t abort_code_of(const std::error_code& ec) noexcept;

// The throwing form's exception: names the node, the object and the abort.
class SdoError : public std::system_error {
 public:
  SdoError(std::error_code ec, std::uint8_t node, std::uint16_t index, std::uint8_t sub);
  std::uint8_t node() const noexcept { return node_; }
  std::uint16_t index() const noexcept { return index_; }
  std::uint8_t sub_index() const noexcept { return sub_; }

 private:
  std::uint8_t node_;
  std::uint16_t index_;
  std::uint8_t sub_;
};

}  // namespace wavebench::canopen

template <>
struct std::is_error_code_enum<wavebench::canopen::SdoAbort> : std::true_type {};
