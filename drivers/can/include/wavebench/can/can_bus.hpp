#pragma once
// The bus interface every CAN user talks to: send frames, subscribe to received frames and to
// controller error events. All handlers run on the bus's io_context and must not throw.

#include <boost/asio/io_context.hpp>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <span>
#include <string_view>
#include <system_error>
#include <vector>

#include "wavebench/can/frame.hpp"

namespace wavebench::can {

enum class BusEventKind {
  error_warning,  // an error counter passed 96
  error_passive,  // an error counter passed 127
  bus_off,        // transmit error counter passed 255: the controller left the bus
  restarted,      // the controller was restarted after bus-off
  error_active,   // back below the warning level
  protocol,       // bit/stuff/form error, lost arbitration, missing ACK, transceiver fault
  overflow,       // a receive or transmit buffer overflowed
};

struct BusEvent {
  BusEventKind kind;
  Frame frame{};  // the error frame behind the event (empty for synthesised events)
};

std::string_view to_string(BusEventKind kind) noexcept;

// Matches like a Linux CAN_RAW filter: (raw_id & mask) == (id & mask), negated when `inverted`.
struct FrameFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool inverted = false;
  bool matches(const Frame& frame) const noexcept;
};

class CanBus {
 public:
  using FrameHandler = std::function<void(const Frame&)>;
  using EventHandler = std::function<void(const BusEvent&)>;

  // Unsubscribes when destroyed; may outlive the bus.
  class Subscription {
   public:
    Subscription() = default;
    Subscription(Subscription&&) noexcept = default;
    Subscription& operator=(Subscription&& other) noexcept;
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;
    ~Subscription();
    void reset() noexcept;

   private:
    friend class CanBus;
    explicit Subscription(std::function<void()> cancel) : cancel_(std::move(cancel)) {}
    std::function<void()> cancel_;
  };

  CanBus();
  virtual ~CanBus();
  CanBus(const CanBus&) = delete;
  CanBus& operator=(const CanBus&) = delete;

  void send(const Frame& frame);  // throws std::system_error
  virtual void send(const Frame& frame, std::error_code& ec) noexcept = 0;
  // Only frames matching at least one filter are delivered; the default accepts everything.
  virtual void set_filters(std::span<const FrameFilter> filters) = 0;
  virtual boost::asio::io_context& context() noexcept = 0;
  virtual std::string_view name() const noexcept = 0;

  [[nodiscard]] Subscription on_frame(FrameHandler handler);
  [[nodiscard]] Subscription on_event(EventHandler handler);

  // How many received frames were handed to subscribers (for statistics and benchmarks).
  std::uint64_t frames_received() const noexcept { return frames_received_; }

 protected:
  void deliver(const Frame& frame) noexcept;
  void deliver(const BusEvent& event) noexcept;

 private:
  template <typename Handler>
  struct HandlerList {
    std::list<Handler> handlers;
    int depth = 0;
    bool dirty = false;
  };
  template <typename Handler, typename Arg>
  static void dispatch(HandlerList<Handler>& list, const Arg& arg) noexcept;
  template <typename Handler>
  static Subscription subscribe(const std::shared_ptr<HandlerList<Handler>>& list, Handler h);

  std::shared_ptr<HandlerList<FrameHandler>> frame_handlers_;
  std::shared_ptr<HandlerList<EventHandler>> event_handlers_;
  std::uint64_t frames_received_ = 0;
};

}  // namespace wavebench::can
