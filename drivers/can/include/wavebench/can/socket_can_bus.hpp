#pragma once
// A raw CAN_RAW SocketCAN socket driven by Boost.Asio: kernel receive timestamps
// (SO_TIMESTAMPNS), kernel-side filters, and controller error frames turned into bus events.

#include <boost/asio/io_context.hpp>
#include <boost/asio/posix/stream_descriptor.hpp>
#include <string>

#include "wavebench/can/can_bus.hpp"

namespace wavebench::can {

class SocketCanBus final : public CanBus {
 public:
  // Opens and binds the interface; throws std::system_error naming the interface and the step
  // that failed (a kernel without AF_CAN fails at socket()).
  SocketCanBus(boost::asio::io_context& io, std::string interface_name);
  ~SocketCanBus() override;

  using CanBus::send;
  void send(const Frame& frame, std::error_code& ec) noexcept override;
  void set_filters(std::span<const FrameFilter> filters) override;
  boost::asio::io_context& context() noexcept override { return io_; }
  std::string_view name() const noexcept override { return interface_name_; }
  // Whether our own transmitted frames are also received (CAN_RAW_RECV_OWN_MSGS).
  void receive_own(bool on);

 private:
  void start_read();
  void read_ready() noexcept;

  boost::asio::io_context& io_;
  std::string interface_name_;
  boost::asio::posix::stream_descriptor socket_;
  std::shared_ptr<bool> alive_;
};

}  // namespace wavebench::can
