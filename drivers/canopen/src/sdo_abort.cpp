#include "wavebench/canopen/sdo_abort.hpp"

#include <fmt/format.h>

namespace wavebench::canopen {

namespace {

const char* known_text(std::uint32_t code) noexcept {
  switch (static_cast<SdoAbort>(code)) {
    case SdoAbort::toggle_bit:
      return "toggle bit not alternated";
    case SdoAbort::timeout:
      return "SDO protocol timed out";
    case SdoAbort::invalid_command:
      return "client/server command specifier not valid or unknown";
    case SdoAbort::invalid_block_size:
      return "invalid block size";
    case SdoAbort::invalid_sequence:
      return "invalid sequence number";
    case SdoAbort::crc_error:
      return "CRC error";
    case SdoAbort::out_of_memory:
      return "out of memory";
    case SdoAbort::unsupported_access:
      return "unsupported access to an object";
    case SdoAbort::write_only:
      return "attempt to read a write only object";
    case SdoAbort::read_only:
      return "attempt to write a read only object";
    case SdoAbort::no_object:
      return "object does not exist in the object dictionary";
    case SdoAbort::not_mappable:
      return "object cannot be mapped to the PDO";
    case SdoAbort::pdo_too_long:
      return "the number and length of the objects to be mapped would exceed PDO length";
    case SdoAbort::parameter_incompatible:
      return "general parameter incompatibility reason";
    case SdoAbort::device_incompatible:
      return "general internal incompatibility in the device";
    case SdoAbort::hardware_error:
      return "access failed due to a hardware error";
    case SdoAbort::length_mismatch:
      return "data type does not match, length of service parameter does not match";
    case SdoAbort::length_too_high:
      return "data type does not match, length of service parameter too high";
    case SdoAbort::length_too_low:
      return "data type does not match, length of service parameter too low";
    case SdoAbort::no_sub_index:
      return "sub-index does not exist";
    case SdoAbort::invalid_value:
      return "invalid value for parameter (download only)";
    case SdoAbort::value_too_high:
      return "value of parameter written too high (download only)";
    case SdoAbort::value_too_low:
      return "value of parameter written too low (download only)";
    case SdoAbort::max_below_min:
      return "maximum value is less than minimum value";
    case SdoAbort::no_resource:
      return "resource not available: SDO connection";
    case SdoAbort::general:
      return "general error";
    case SdoAbort::data_transfer:
      return "data cannot be transferred or stored to the application";
    case SdoAbort::local_control:
      return "data cannot be transferred or stored to the application because of local control";
    case SdoAbort::device_state:
      return "data cannot be transferred or stored to the application because of the present "
             "device state";
    case SdoAbort::no_dictionary:
      return "object dictionary dynamic generation fails or no object dictionary is present";
    case SdoAbort::no_data:
      return "no data available";
  }
  return nullptr;
}

class SdoCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "sdo"; }
  std::string message(int value) const override {
    return abort_text(static_cast<std::uint32_t>(value));
  }
};

}  // namespace

const std::error_category& sdo_category() noexcept {
  static const SdoCategory category;
  return category;
}

std::error_code make_error_code(SdoAbort abort) noexcept {
  return {static_cast<int>(abort), sdo_category()};
}

std::string abort_text(std::uint32_t code) {
  const char* text = known_text(code);
  return fmt::format("{:08X} {}", code, text != nullptr ? text : "unknown abort code");
}

std::uint32_t abort_code_of(const std::error_code& ec) noexcept {
  if (ec.category() == sdo_category()) return static_cast<std::uint32_t>(ec.value());
  if (ec == std::errc::timed_out) return static_cast<std::uint32_t>(SdoAbort::timeout);
  return static_cast<std::uint32_t>(SdoAbort::general);
}

SdoError::SdoError(std::error_code ec, std::uint8_t node, std::uint16_t index, std::uint8_t sub)
    : std::system_error(ec, fmt::format("SDO node {} object {:04X}:{:02X}", node, index, sub)),
      node_(node),
      index_(index),
      sub_(sub) {}

}  // namespace wavebench::canopen
