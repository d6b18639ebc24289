#pragma once
// EMCY consumer (CiA 301 §7.2.7): error code, error register and the vendor bytes of every
// emergency a node sends; error code 0x0000 means "error reset / no error".

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/cob_id.hpp"

namespace wavebench::canopen {

struct Emergency {
  NodeId node = 0;
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;  // 0x1001
  std::array<std::uint8_t, 5> vendor{};
  bool is_reset() const noexcept { return error_code == 0; }
};

std::optional<Emergency> decode_emcy(const can::Frame& frame) noexcept;
can::Frame emcy_frame(const Emergency& emergency);
// The CiA 301 error code class, e.g. "current" for 0x2310.
std::string describe_emcy_code(std::uint16_t code);

class EmcyConsumer {
 public:
  using Hook = std::function<void(const Emergency&)>;
  EmcyConsumer(can::CanBus& bus, Hook hook);
  EmcyConsumer(const EmcyConsumer&) = delete;
  EmcyConsumer& operator=(const EmcyConsumer&) = delete;
  std::uint64_t received() const noexcept { return count_; }

 private:
  Hook hook_;
  can::CanBus::Subscription subscription_;
  std::uint64_t count_ = 0;
};

}  // namespace wavebench::canopen
