#pragma once
// An in-process CAN bus: any number of endpoints, every frame sent by one endpoint is delivered
// to every other endpoint (as SocketCAN's loopback does), in send order, through one io_context.
// Deterministic: delivery happens only while the io_context runs, one posted handler per frame.
// Frames are stamped on delivery, except a frame sent with a timestamp, which keeps it (tests
// replay frames that arrived while the receiver's loop was held).

#include <boost/asio/io_context.hpp>
#include <memory>
#include <string>
#include <vector>

#include "wavebench/can/can_bus.hpp"

namespace wavebench::can {

class VirtualCanEndpoint;

class VirtualCanBus {
 public:
  explicit VirtualCanBus(boost::asio::io_context& io);
  ~VirtualCanBus();
  VirtualCanBus(const VirtualCanBus&) = delete;
  VirtualCanBus& operator=(const VirtualCanBus&) = delete;

  std::unique_ptr<VirtualCanEndpoint> endpoint(std::string name = "vcan");

  // Simulates a controller event seen by every endpoint (bus-off, error-passive, ...).
  void raise(BusEventKind kind);
  // Frames that crossed the bus, in order (for tests that compare whole conversations).
  const std::vector<Frame>& log() const noexcept { return log_; }
  void record(bool on) noexcept { recording_ = on; }
  void clear_log() noexcept { log_.clear(); }
  boost::asio::io_context& context() noexcept { return io_; }

 private:
  friend class VirtualCanEndpoint;
  void transmit(const VirtualCanEndpoint* from, const Frame& frame);
  void detach(VirtualCanEndpoint* endpoint) noexcept;

  boost::asio::io_context& io_;
  std::shared_ptr<std::vector<VirtualCanEndpoint*>> endpoints_;
  std::vector<Frame> log_;
  bool recording_ = true;
};

class VirtualCanEndpoint final : public CanBus {
 public:
  ~VirtualCanEndpoint() override;
  using CanBus::send;
  void send(const Frame& frame, std::error_code& ec) noexcept override;
  void set_filters(std::span<const FrameFilter> filters) override;
  boost::asio::io_context& context() noexcept override { return bus_->context(); }
  std::string_view name() const noexcept override { return name_; }
  // A bus-off endpoint refuses to send (ENETDOWN) until restarted.
  void set_bus_off(bool off) noexcept { bus_off_ = off; }

 private:
  friend class VirtualCanBus;
  VirtualCanEndpoint(VirtualCanBus& bus, std::string name);
  void receive(const Frame& frame) noexcept;
  void notify(const BusEvent& event) noexcept { deliver(event); }

  VirtualCanBus* bus_;
  std::string name_;
  std::vector<FrameFilter> filters_;
  bool bus_off_ = false;
};

}  // namespace wavebench::can
