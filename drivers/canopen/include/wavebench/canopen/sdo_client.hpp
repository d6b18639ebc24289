#pragma once
// SDO client for one server node: expedited and segmented upload and download, CiA 301 §7.2.4.
// Every call comes in three forms: asynchronous (any Boost.Asio completion token: a handler, or
// boost::asio::use_awaitable so a coroutine suspends until the transfer completes), throwing
// (SdoError), and std::error_code&. The blocking forms wait in the one event loop
// (wavebench/can/event_loop.hpp) until the transfer completes, so they must not be called from a
// handler running on that io_context; the acquisition path never calls them.
// A completion handler that throws does not become a transfer error: its exception leaves the
// event loop unchanged and reaches whoever waits there (the std::error_code& forms included: the
// code reports the transfer, an exception is not the transfer's).
// One transfer is on the wire at a time; further requests queue in order.

#include <boost/asio/async_result.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include "wavebench/can/can_bus.hpp"
#include "wavebench/canopen/cob_id.hpp"
#include "wavebench/canopen/sdo_abort.hpp"

namespace wavebench::canopen {

class SdoClient {
 public:
  using UploadHandler = std::function<void(std::error_code, std::vector<std::uint8_t>)>;
  using DownloadHandler = std::function<void(std::error_code)>;

  SdoClient(can::CanBus& bus, NodeId node,
            std::chrono::milliseconds timeout = std::chrono::milliseconds(500));
  ~SdoClient();
  SdoClient(const SdoClient&) = delete;
  SdoClient& operator=(const SdoClient&) = delete;

  NodeId node() const noexcept { return node_; }
  can::CanBus& bus() noexcept { return bus_; }
  void set_timeout(std::chrono::milliseconds timeout) noexcept { timeout_ = timeout; }
  std::chrono::milliseconds timeout() const noexcept { return timeout_; }
  // Whether to send an abort frame when the server stays silent past the timeout (default on).
  void set_abort_on_timeout(bool on) noexcept { abort_on_timeout_ = on; }
  // Uploads by SDO block transfer (CiA 301 §7.2.4.3.9; no CRC, blocks of `block_size`
  // segments), falling back to segmented when the server answers "command not valid".
  void set_block_upload(bool on, std::uint8_t block_size = 127) noexcept {
    block_upload_ = on;
    block_size_ = block_size == 0 || block_size > 127 ? std::uint8_t{127} : block_size;
  }

  // Completes with (std::error_code, bytes); with use_awaitable `co_await` yields that pair.
  template <typename CompletionToken>
  auto async_upload(std::uint16_t index, std::uint8_t sub, CompletionToken&& token) {
    return boost::asio::async_initiate<CompletionToken,
                                       void(std::error_code, std::vector<std::uint8_t>)>(
        [this, index, sub](auto handler) {
          queue_upload(index, sub, copyable<UploadHandler>(std::move(handler)));
        },
        token);
  }
  // Completes with (std::error_code); with use_awaitable `co_await` yields the code.
  template <typename CompletionToken>
  auto async_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data,
                      CompletionToken&& token) {
    return boost::asio::async_initiate<CompletionToken, void(std::error_code)>(
        [this, index, sub](auto handler, std::vector<std::uint8_t> bytes) {
          queue_download(index, sub, std::move(bytes),
                         copyable<DownloadHandler>(std::move(handler)));
        },
        token, std::move(data));
  }

  std::vector<std::uint8_t> upload(std::uint16_t index, std::uint8_t sub);
  std::vector<std::uint8_t> upload(std::uint16_t index, std::uint8_t sub, std::error_code& ec);
  void download(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data);
  void download(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data,
                std::error_code& ec);

  // Typed access for arithmetic objects (little-endian, exact size checked on read).
  template <typename T>
  T read(std::uint16_t index, std::uint8_t sub) {
    std::error_code ec;
    T v = read<T>(index, sub, ec);
    if (ec) throw SdoError(ec, node_, index, sub);
    return v;
  }
  template <typename T>
  T read(std::uint16_t index, std::uint8_t sub, std::error_code& ec) {
    static_assert(std::is_arithmetic_v<T>);
    const auto bytes = upload(index, sub, ec);
    if (ec) return T{};
    if (bytes.size() != sizeof(T)) {
      ec = make_error_code(SdoAbort::length_mismatch);
      return T{};
    }
    T v{};
    std::memcpy(&v, bytes.data(), sizeof(T));  // host is little-endian, as CANopen
    return v;
  }
  template <typename T>
  void write(std::uint16_t index, std::uint8_t sub, T value) {
    std::error_code ec;
    write<T>(index, sub, value, ec);
    if (ec) throw SdoError(ec, node_, index, sub);
  }
  template <typename T>
  void write(std::uint16_t index, std::uint8_t sub, T value, std::error_code& ec) {
    static_assert(std::is_arithmetic_v<T>);
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    download(index, sub, bytes, ec);
  }

  // Feeds a frame from the server (the client subscribes itself; exposed for fuzzing).
  void on_frame(const can::Frame& frame) noexcept;
  bool busy() const noexcept { return active_; }

 private:
  struct Request {
    bool upload = true;
    bool block = false;
    std::uint16_t index = 0;
    std::uint8_t sub = 0;
    std::vector<std::uint8_t> data;
    UploadHandler on_upload;
    DownloadHandler on_download;
  };
  enum class Phase { initiate, segment, block_data, block_end };

  // Handlers from completion tokens may be move-only (a coroutine's); the queue keeps
  // std::function, so they are held by a shared pointer.
  template <typename Function, typename Handler>
  static Function copyable(Handler handler) {
    auto held = std::make_shared<Handler>(std::move(handler));
    return [held](auto&&... args) { (*held)(std::forward<decltype(args)>(args)...); };
  }
  void queue_upload(std::uint16_t index, std::uint8_t sub, UploadHandler handler);
  void queue_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data,
                      DownloadHandler handler);
  void start_next() noexcept;
  void send_current() noexcept;
  void send_frame(const can::Frame& frame) noexcept;
  void arm_timer() noexcept;
  void on_timeout() noexcept;
  void send_abort(std::uint32_t code) noexcept;
  void finish(std::error_code ec) noexcept;
  void handle_upload(const can::Frame& frame) noexcept;
  void handle_block_upload(const can::Frame& frame) noexcept;
  void handle_download(const can::Frame& frame) noexcept;
  void send_download_segment() noexcept;
  void fail_with_abort(SdoAbort code) noexcept;

  can::CanBus& bus_;
  NodeId node_;
  std::chrono::milliseconds timeout_;
  bool abort_on_timeout_ = true;
  bool block_upload_ = false;
  std::uint8_t block_size_ = 127;
  std::uint8_t sequence_ = 0;  // block upload: last sequence number received in this block
  boost::asio::steady_timer timer_;
  can::CanBus::Subscription subscription_;
  std::deque<Request> queue_;
  bool active_ = false;
  Request current_;
  Phase phase_ = Phase::initiate;
  bool toggle_ = false;
  std::size_t offset_ = 0;         // download: bytes sent
  std::size_t expected_size_ = 0;  // upload: size indicated by the server
  bool size_indicated_ = false;
  std::vector<std::uint8_t> received_;
  can::Frame last_sent_;
  std::uint64_t generation_ = 0;  // distinguishes a stale timer from the current one
};

}  // namespace wavebench::canopen
