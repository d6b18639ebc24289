// CiA 301 data types and EDS access types: names and sizes.
#include <fmt/format.h>

#include "wavebench/canopen/eds.hpp"

namespace wavebench::canopen {

std::string data_type_name(std::uint16_t type) {
  switch (type) {
    case datatype::kBoolean:
      return "BOOLEAN";
    case datatype::kInteger8:
      return "INTEGER8";
    case datatype::kInteger16:
      return "INTEGER16";
    case datatype::kInteger32:
      return "INTEGER32";
    case datatype::kUnsigned8:
      return "UNSIGNED8";
    case datatype::kUnsigned16:
      return "UNSIGNED16";
    case datatype::kUnsigned32:
      return "UNSIGNED32";
    case datatype::kReal32:
      return "REAL32";
    case datatype::kVisibleString:
      return "VISIBLE_STRING";
    case datatype::kOctetString:
      return "OCTET_STRING";
    case datatype::kUnicodeString:
      return "UNICODE_STRING";
    case datatype::kTimeOfDay:
      return "TIME_OF_DAY";
    case datatype::kTimeDifference:
      return "TIME_DIFFERENCE";
    case datatype::kDomain:
      return "DOMAIN";
    case datatype::kInteger24:
      return "INTEGER24";
    case datatype::kReal64:
      return "REAL64";
    case datatype::kInteger40:
      return "INTEGER40";
    case datatype::kInteger48:
      return "INTEGER48";
    case datatype::kInteger56:
      return "INTEGER56";
    case datatype::kInteger64:
      return "INTEGER64";
    case datatype::kUnsigned24:
      return "UNSIGNED24";
    case datatype::kUnsigned40:
      return "UNSIGNED40";
    case datatype::kUnsigned48:
      return "UNSIGNED48";
    case datatype::kUnsigned56:
      return "UNSIGNED56";
    case datatype::kUnsigned64:
      return "UNSIGNED64";
    default:
      return fmt::format("type 0x{:04X}", type);
  }
}

std::size_t data_type_size(std::uint16_t type) noexcept {
  switch (type) {
    case datatype::kBoolean:
    case datatype::kInteger8:
    case datatype::kUnsigned8:
      return 1;
    case datatype::kInteger16:
    case datatype::kUnsigned16:
      return 2;
    case datatype::kInteger24:
    case datatype::kUnsigned24:
      return 3;
    case datatype::kInteger32:
    case datatype::kUnsigned32:
    case datatype::kReal32:
      return 4;
    case datatype::kInteger40:
    case datatype::kUnsigned40:
      return 5;
    case datatype::kInteger48:
    case datatype::kUnsigned48:
    case datatype::kTimeOfDay:
    case datatype::kTimeDifference:
      return 6;
    case datatype::kInteger56:
    case datatype::kUnsigned56:
      return 7;
    case datatype::kReal64:
    case datatype::kInteger64:
    case datatype::kUnsigned64:
      return 8;
    default:
      return 0;
  }
}

bool is_unsigned_type(std::uint16_t type) noexcept {
  switch (type) {
    case datatype::kBoolean:
    case datatype::kUnsigned8:
    case datatype::kUnsigned16:
    case datatype::kUnsigned24:
    case datatype::kUnsigned32:
    case datatype::kUnsigned40:
    case datatype::kUnsigned48:
    case datatype::kUnsigned56:
    case datatype::kUnsigned64:
      return true;
    default:
      return false;
  }
}

bool is_integer_type(std::uint16_t type) noexcept {
  switch (type) {
    case datatype::kInteger8:
    case datatype::kInteger16:
    case datatype::kInteger24:
    case datatype::kInteger32:
    case datatype::kInteger40:
    case datatype::kInteger48:
    case datatype::kInteger56:
    case datatype::kInteger64:
      return true;
    default:
      return is_unsigned_type(type);
  }
}

std::string_view to_string(EdsAccess access) noexcept {
  switch (access) {
    case EdsAccess::kRo:
      return "ro";
    case EdsAccess::kWo:
      return "wo";
    case EdsAccess::kRw:
      return "rw";
    case EdsAccess::kRwr:
      return "rwr";
    case EdsAccess::kRww:
      return "rww";
    case EdsAccess::kConst:
      return "const";
  }
  return "?";
}

}  // namespace wavebench::canopen
