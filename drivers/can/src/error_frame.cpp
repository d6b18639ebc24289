#include "wavebench/can/error_frame.hpp"

#include <linux/can/error.h>

namespace wavebench::can {

std::vector<BusEvent> classify_error_frame(const Frame& frame) {
  std::vector<BusEvent> events;
  if (!frame.error) return events;
  const std::uint32_t cls = frame.id;
  const std::uint8_t ctrl = frame.len > 1 ? frame.data[1] : 0;
  auto add = [&](BusEventKind kind) { events.push_back(BusEvent{kind, frame}); };
  if ((cls & CAN_ERR_BUSOFF) != 0U) add(BusEventKind::bus_off);
  if ((cls & CAN_ERR_CRTL) != 0U) {
    if ((ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0U) {
      add(BusEventKind::error_passive);
    }
    if ((ctrl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0U) {
      add(BusEventKind::error_warning);
    }
    if ((ctrl & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0U) {
      add(BusEventKind::overflow);
    }
#ifdef CAN_ERR_CRTL_ACTIVE
    if ((ctrl & CAN_ERR_CRTL_ACTIVE) != 0U) add(BusEventKind::error_active);
#endif
  }
  if ((cls & CAN_ERR_RESTARTED) != 0U) add(BusEventKind::restarted);
  if ((cls & (CAN_ERR_PROT | CAN_ERR_ACK | CAN_ERR_LOSTARB | CAN_ERR_TRX | CAN_ERR_BUSERROR |
              CAN_ERR_TX_TIMEOUT)) != 0U) {
    add(BusEventKind::protocol);
  }
  return events;
}

}  // namespace wavebench::can
