#include "wavebench/canopen/emcy.hpp"

#include <fmt/format.h>

namespace wavebench::canopen {

std::optional<Emergency> decode_emcy(const can::Frame& frame) noexcept {
  if (frame.extended || frame.rtr || frame.error) return std::nullopt;
  if (frame.id <= kEmcyBase || frame.id > kEmcyBase + 127) return std::nullopt;
  // Accept short EMCYs (some devices send only code and register); missing bytes read as zero.
  if (frame.len < 3) return std::nullopt;
  Emergency e;
  e.node = static_cast<NodeId>(frame.id - kEmcyBase);
  e.error_code = static_cast<std::uint16_t>(frame.data[0] | (frame.data[1] << 8));
  e.error_register = frame.data[2];
  for (std::size_t i = 0; i < 5 && 3 + i < frame.len; ++i) e.vendor[i] = frame.data[3 + i];
  return e;
}

can::Frame emcy_frame(const Emergency& e) {
  return can::Frame::make(
      emcy_cob_id(e.node),
      {static_cast<std::uint8_t>(e.error_code & 0xFF), static_cast<std::uint8_t>(e.error_code >> 8),
       e.error_register, e.vendor[0], e.vendor[1], e.vendor[2], e.vendor[3], e.vendor[4]});
}

std::string describe_emcy_code(std::uint16_t code) {
  const char* what = "device specific";
  switch (code >> 12) {
    case 0x0:
      what = code == 0 ? "error reset or no error" : "generic";
      break;
    case 0x1:
      what = "generic error";
      break;
    case 0x2:
      what = "current";
      break;
    case 0x3:
      what = "voltage";
      break;
    case 0x4:
      what = "temperature";
      break;
    case 0x5:
      what = "device hardware";
      break;
    case 0x6:
      what = "device software";
      break;
    case 0x7:
      what = "additional modules";
      break;
    case 0x8:
      what = (code & 0xFF00) == 0x8100   ? "communication"
             : (code & 0xFF00) == 0x8200 ? "protocol error"
             : (code & 0xFFF0) == 0x8610 ? "following error"
                                         : "monitoring";
      break;
    case 0x9:
      what = "external error";
      break;
    case 0xF:
      what = "additional functions";
      break;
    default:
      break;
  }
  return fmt::format("{:04X} {}", code, what);
}

EmcyConsumer::EmcyConsumer(can::CanBus& bus, Hook hook) : hook_(std::move(hook)) {
  subscription_ = bus.on_frame([this](const can::Frame& f) {
    if (f.id <= kEmcyBase || f.id > kEmcyBase + 127) return;
    if (auto e = decode_emcy(f)) {
      ++count_;
      if (hook_) hook_(*e);
    }
  });
}

}  // namespace wavebench::canopen
