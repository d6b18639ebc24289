#include "wavebench/can/can_bus.hpp"

namespace wavebench::can {

std::string_view to_string(BusEventKind kind) noexcept {
  switch (kind) {
    case BusEventKind::error_warning:
      return "error-warning";
    case BusEventKind::error_passive:
      return "error-passive";
    case BusEventKind::bus_off:
      return "bus-off";
    case BusEventKind::restarted:
      return "restarted";
    case BusEventKind::error_active:
      return "error-active";
    case BusEventKind::protocol:
      return "protocol-error";
    case BusEventKind::overflow:
      return "overflow";
  }
  return "unknown";
}

bool FrameFilter::matches(const Frame& frame) const noexcept {
  const bool hit = (frame.raw_id() & mask) == (id & mask);
  return hit != inverted;
}

CanBus::Subscription& CanBus::Subscription::operator=(Subscription&& other) noexcept {
  if (this != &other) {
    reset();
    cancel_ = std::move(other.cancel_);
    other.cancel_ = nullptr;
  }
  return *this;
}

CanBus::Subscription::~Subscription() {
  reset();
}

void CanBus::Subscription::reset() noexcept {
  if (cancel_) {
    auto cancel = std::move(cancel_);
    cancel_ = nullptr;
    cancel();
  }
}

CanBus::CanBus()
    : frame_handlers_(std::make_shared<HandlerList<FrameHandler>>()),
      event_handlers_(std::make_shared<HandlerList<EventHandler>>()) {}

CanBus::~CanBus() = default;

void CanBus::send(const Frame& frame) {
  std::error_code ec;
  send(frame, ec);
  if (ec)
    throw std::system_error(ec,
                            "CAN send on " + std::string(name()) + " (" + to_string(frame) + ")");
}

template <typename Handler>
CanBus::Subscription CanBus::subscribe(const std::shared_ptr<HandlerList<Handler>>& list,
                                       Handler h) {
  list->handlers.push_back(std::move(h));
  auto it = std::prev(list->handlers.end());
  std::weak_ptr<HandlerList<Handler>> weak = list;
  return Subscription([weak, it] {
    auto l = weak.lock();
    if (!l) return;
    // Erasing inside a dispatch would pull the node from under the loop: mark it instead.
    if (l->depth > 0) {
      *it = nullptr;
      l->dirty = true;
    } else {
      l->handlers.erase(it);
    }
  });
}

template <typename Handler, typename Arg>
void CanBus::dispatch(HandlerList<Handler>& list, const Arg& arg) noexcept {
  ++list.depth;
  for (auto it = list.handlers.begin(); it != list.handlers.end(); ++it) {
    if (*it) (*it)(arg);
  }
  if (--list.depth == 0 && list.dirty) {
    list.handlers.remove_if([](const Handler& h) { return !h; });
    list.dirty = false;
  }
}

CanBus::Subscription CanBus::on_frame(FrameHandler handler) {
  return subscribe(frame_handlers_, std::move(handler));
}

CanBus::Subscription CanBus::on_event(EventHandler handler) {
  return subscribe(event_handlers_, std::move(handler));
}

void CanBus::deliver(const Frame& frame) noexcept {
  ++frames_received_;
  auto keep = frame_handlers_;
  dispatch(*keep, frame);
}

void CanBus::deliver(const BusEvent& event) noexcept {
  auto keep = event_handlers_;
  dispatch(*keep, event);
}

}  // namespace wavebench::can
