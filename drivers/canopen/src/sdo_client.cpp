#include "wavebench/canopen/sdo_client.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>
#include <exception>

#include "wavebench/can/event_loop.hpp"

namespace wavebench::canopen {

namespace {

// Command specifiers (upper three bits of byte 0).
constexpr std::uint8_t kCcsDownloadSegment = 0x00;
constexpr std::uint8_t kCcsInitiateDownload = 0x20;
constexpr std::uint8_t kCcsInitiateUpload = 0x40;
constexpr std::uint8_t kCcsUploadSegment = 0x60;
constexpr std::uint8_t kCcsBlockUpload = 0xA0;
constexpr std::uint8_t kScsBlockUpload = 0xC0;
constexpr std::uint8_t kAbort = 0x80;
constexpr std::uint8_t kScsUploadSegment = 0x00;
constexpr std::uint8_t kScsDownloadSegment = 0x20;
constexpr std::uint8_t kScsInitiateUpload = 0x40;
constexpr std::uint8_t kScsInitiateDownload = 0x60;
constexpr std::uint8_t kToggle = 0x10;

std::uint32_t le32(const std::uint8_t* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

can::Frame request(NodeId node, std::uint8_t command) {
  can::Frame f;
  f.id = sdo_rx_cob_id(node);
  f.len = 8;
  f.data[0] = command;
  return f;
}

void put_mux(can::Frame& f, std::uint16_t index, std::uint8_t sub) noexcept {
  f.data[1] = static_cast<std::uint8_t>(index & 0xFF);
  f.data[2] = static_cast<std::uint8_t>(index >> 8);
  f.data[3] = sub;
}

bool mux_matches(const can::Frame& f, std::uint16_t index, std::uint8_t sub) noexcept {
  return f.len >= 4 && f.data[1] == (index & 0xFF) && f.data[2] == (index >> 8) && f.data[3] == sub;
}

}  // namespace

SdoClient::SdoClient(can::CanBus& bus, NodeId node, std::chrono::milliseconds timeout)
    : bus_(bus), node_(node), timeout_(timeout), timer_(bus.context()) {
  if (!valid_node(node)) {
    throw std::invalid_argument("SDO client node id " + std::to_string(node) + ": expected 1..127");
  }
  subscription_ = bus_.on_frame([this](const can::Frame& f) {
    if (!f.extended && !f.rtr && f.id == sdo_tx_cob_id(node_)) on_frame(f);
  });
}

SdoClient::~SdoClient() {
  subscription_.reset();
  timer_.cancel();
}

void SdoClient::queue_upload(std::uint16_t index, std::uint8_t sub, UploadHandler handler) {
  Request r;
  r.upload = true;
  r.block = block_upload_;
  r.index = index;
  r.sub = sub;
  r.on_upload = std::move(handler);
  queue_.push_back(std::move(r));
  if (!active_) start_next();
}

void SdoClient::queue_download(std::uint16_t index, std::uint8_t sub,
                               std::vector<std::uint8_t> data, DownloadHandler handler) {
  Request r;
  r.upload = false;
  r.index = index;
  r.sub = sub;
  r.data = std::move(data);
  r.on_download = std::move(handler);
  queue_.push_back(std::move(r));
  if (!active_) start_next();
}

void SdoClient::start_next() noexcept {
  if (active_ || queue_.empty()) return;
  current_ = std::move(queue_.front());
  queue_.pop_front();
  active_ = true;
  phase_ = Phase::initiate;
  toggle_ = false;
  offset_ = 0;
  expected_size_ = 0;
  size_indicated_ = false;
  received_.clear();
  send_current();
}

void SdoClient::send_current() noexcept {
  if (current_.upload && current_.block) {
    auto f = request(node_, kCcsBlockUpload);  // initiate, client CRC support off
    put_mux(f, current_.index, current_.sub);
    f.data[4] = block_size_;
    f.data[5] = 0;  // protocol switch threshold: never switch
    send_frame(f);
    return;
  }
  if (current_.upload) {
    auto f = request(node_, kCcsInitiateUpload);
    put_mux(f, current_.index, current_.sub);
    send_frame(f);
    return;
  }
  const std::size_t n = current_.data.size();
  if (n >= 1 && n <= 4) {
    // Expedited, size indicated: 0x2F/0x2B/0x27/0x23 for 1/2/3/4 bytes.
    auto f =
        request(node_, static_cast<std::uint8_t>(kCcsInitiateDownload | ((4 - n) << 2) | 0x03));
    put_mux(f, current_.index, current_.sub);
    std::copy_n(current_.data.begin(), n, f.data.begin() + 4);
    send_frame(f);
    return;
  }
  auto f = request(node_, kCcsInitiateDownload | 0x01);  // segmented, size indicated
  put_mux(f, current_.index, current_.sub);
  const auto size = static_cast<std::uint32_t>(n);
  for (int i = 0; i < 4; ++i) f.data[4 + i] = static_cast<std::uint8_t>(size >> (8 * i));
  send_frame(f);
}

void SdoClient::send_frame(const can::Frame& frame) noexcept {
  last_sent_ = frame;
  std::error_code ec;
  bus_.send(frame, ec);
  if (ec) {
    finish(ec);
    return;
  }
  arm_timer();
}

void SdoClient::arm_timer() noexcept {
  const auto generation = ++generation_;
  timer_.expires_after(timeout_);
  timer_.async_wait([this, generation](const boost::system::error_code& ec) {
    if (ec == boost::asio::error::operation_aborted) return;
    if (generation != generation_ || !active_) return;
    on_timeout();
  });
}

void SdoClient::on_timeout() noexcept {
  if (abort_on_timeout_) send_abort(static_cast<std::uint32_t>(SdoAbort::timeout));
  finish(make_error_code(SdoAbort::timeout));
}

void SdoClient::send_abort(std::uint32_t code) noexcept {
  auto f = request(node_, kAbort);
  put_mux(f, current_.index, current_.sub);
  for (int i = 0; i < 4; ++i) f.data[4 + i] = static_cast<std::uint8_t>(code >> (8 * i));
  std::error_code ignored;
  bus_.send(f, ignored);
}

void SdoClient::fail_with_abort(SdoAbort code) noexcept {
  send_abort(static_cast<std::uint32_t>(code));
  finish(make_error_code(code));
}

void SdoClient::finish(std::error_code ec) noexcept {
  ++generation_;
  timer_.cancel();
  Request done = std::move(current_);
  current_ = Request{};
  active_ = false;
  std::vector<std::uint8_t> data = std::move(received_);
  received_.clear();
  if (ec) data.clear();
  try {
    if (done.upload) {
      if (done.on_upload) done.on_upload(ec, std::move(data));
    } else {
      if (done.on_download) done.on_download(ec);
    }
  } catch (...) {
    // The handler's failure is not this transfer's: it leaves the event loop as thrown and
    // reaches whoever waits there, while the queue goes on.
    boost::asio::post(bus_.context(),
                      [failure = std::current_exception()] { std::rethrow_exception(failure); });
  }
  start_next();
}

void SdoClient::on_frame(const can::Frame& frame) noexcept {
  if (!active_ || frame.len < 1) return;
  if (frame.data[0] == kAbort) {
    // An abort for another object is a stale reply: ignore it.
    if (frame.len >= 4 && !mux_matches(frame, current_.index, current_.sub)) return;
    const std::uint32_t code =
        frame.len >= 8 ? le32(&frame.data[4]) : static_cast<std::uint32_t>(SdoAbort::general);
    if (current_.upload && current_.block && phase_ == Phase::initiate &&
        code == static_cast<std::uint32_t>(SdoAbort::invalid_command)) {
      // No block transfer on this server: the same upload, segmented.
      current_.block = false;
      send_current();
      return;
    }
    finish(std::error_code(static_cast<int>(code), sdo_category()));
    return;
  }
  if (current_.upload && current_.block) {
    handle_block_upload(frame);
  } else if (current_.upload) {
    handle_upload(frame);
  } else {
    handle_download(frame);
  }
}

void SdoClient::handle_upload(const can::Frame& frame) noexcept {
  const std::uint8_t cmd = frame.data[0];
  if (phase_ == Phase::initiate) {
    if ((cmd & 0xE0) != kScsInitiateUpload) return fail_with_abort(SdoAbort::invalid_command);
    if (!mux_matches(frame, current_.index, current_.sub)) return;  // not ours
    const bool expedited = (cmd & 0x02) != 0;
    const bool sized = (cmd & 0x01) != 0;
    if (expedited) {
      const std::size_t available = frame.len > 4 ? frame.len - 4U : 0U;
      std::size_t size = sized ? 4U - ((cmd >> 2) & 0x03U) : std::min<std::size_t>(4, available);
      if (size > available) return fail_with_abort(SdoAbort::length_mismatch);
      received_.assign(frame.data.begin() + 4, frame.data.begin() + 4 + static_cast<long>(size));
      return finish({});
    }
    if (sized) {
      if (frame.len < 8) return fail_with_abort(SdoAbort::length_mismatch);
      size_indicated_ = true;
      expected_size_ = le32(&frame.data[4]);
    }
    phase_ = Phase::segment;
    toggle_ = false;
    auto f = request(node_, kCcsUploadSegment);
    send_frame(f);
    return;
  }
  if ((cmd & 0xE0) != kScsUploadSegment) return fail_with_abort(SdoAbort::invalid_command);
  if (((cmd & kToggle) != 0) != toggle_) return fail_with_abort(SdoAbort::toggle_bit);
  const std::size_t count = 7U - ((cmd >> 1) & 0x07U);
  const std::size_t available = frame.len - 1U;
  if (count > available) return fail_with_abort(SdoAbort::length_mismatch);
  received_.insert(received_.end(), frame.data.begin() + 1,
                   frame.data.begin() + 1 + static_cast<long>(count));
  if (size_indicated_ && received_.size() > expected_size_) {
    return fail_with_abort(SdoAbort::length_too_high);
  }
  if ((cmd & 0x01) != 0) {
    if (size_indicated_ && received_.size() != expected_size_) {
      return fail_with_abort(SdoAbort::length_too_low);
    }
    return finish({});
  }
  toggle_ = !toggle_;
  auto f = request(node_, static_cast<std::uint8_t>(kCcsUploadSegment | (toggle_ ? kToggle : 0)));
  send_frame(f);
}

void SdoClient::handle_block_upload(const can::Frame& frame) noexcept {
  const std::uint8_t cmd = frame.data[0];
  switch (phase_) {
    case Phase::initiate: {
      if ((cmd & 0xE1) != kScsBlockUpload) return fail_with_abort(SdoAbort::invalid_command);
      if (!mux_matches(frame, current_.index, current_.sub)) return;
      if ((cmd & 0x02) != 0) {
        if (frame.len < 8) return fail_with_abort(SdoAbort::length_mismatch);
        size_indicated_ = true;
        expected_size_ = le32(&frame.data[4]);
      }
      phase_ = Phase::block_data;
      sequence_ = 0;
      send_frame(request(node_, kCcsBlockUpload | 0x03));  // start upload
      return;
    }
    case Phase::block_data: {
      const std::uint8_t seq = cmd & 0x7F;
      const bool last = (cmd & 0x80) != 0;
      if (seq != sequence_ + 1 || seq > block_size_) {
        return fail_with_abort(SdoAbort::invalid_sequence);
      }
      sequence_ = seq;
      received_.insert(received_.end(), frame.data.begin() + 1, frame.data.begin() + frame.len);
      if (received_.size() > (std::size_t{1} << 28)) {
        return fail_with_abort(SdoAbort::out_of_memory);
      }
      if (!last && seq < block_size_) {
        arm_timer();  // the server streams the block: each segment restarts the timeout
        return;
      }
      auto ack = request(node_, kCcsBlockUpload | 0x02);
      ack.data[1] = seq;
      ack.data[2] = block_size_;
      sequence_ = 0;
      if (last) phase_ = Phase::block_end;
      send_frame(ack);
      return;
    }
    case Phase::block_end: {
      if ((cmd & 0xE1) != (kScsBlockUpload | 0x01)) {
        return fail_with_abort(SdoAbort::invalid_command);
      }
      const std::size_t unused = (cmd >> 2) & 0x07U;
      if (unused > received_.size()) return fail_with_abort(SdoAbort::length_mismatch);
      received_.resize(received_.size() - unused);
      if (size_indicated_ && received_.size() != expected_size_) {
        return fail_with_abort(received_.size() < expected_size_ ? SdoAbort::length_too_low
                                                                 : SdoAbort::length_too_high);
      }
      std::error_code ec;
      bus_.send(request(node_, kCcsBlockUpload | 0x01), ec);  // end response
      finish(ec);
      return;
    }
    case Phase::segment:
      return;
  }
}

void SdoClient::handle_download(const can::Frame& frame) noexcept {
  const std::uint8_t cmd = frame.data[0];
  if (phase_ == Phase::initiate) {
    if ((cmd & 0xE0) != kScsInitiateDownload) return fail_with_abort(SdoAbort::invalid_command);
    if (!mux_matches(frame, current_.index, current_.sub)) return;
    const std::size_t n = current_.data.size();
    if (n >= 1 && n <= 4) return finish({});
    phase_ = Phase::segment;
    toggle_ = false;
    send_download_segment();
    return;
  }
  if ((cmd & 0xE0) != kScsDownloadSegment) return fail_with_abort(SdoAbort::invalid_command);
  if (((cmd & kToggle) != 0) != toggle_) return fail_with_abort(SdoAbort::toggle_bit);
  if (offset_ >= current_.data.size()) return finish({});
  toggle_ = !toggle_;
  send_download_segment();
}

void SdoClient::send_download_segment() noexcept {
  const std::size_t remaining = current_.data.size() - offset_;
  const std::size_t n = std::min<std::size_t>(7, remaining);
  const bool last = remaining <= 7;
  auto f = request(node_, static_cast<std::uint8_t>(kCcsDownloadSegment | (toggle_ ? kToggle : 0) |
                                                    ((7 - n) << 1) | (last ? 1 : 0)));
  std::copy_n(current_.data.begin() + static_cast<long>(offset_), n, f.data.begin() + 1);
  offset_ += n;
  send_frame(f);
}

namespace {

// Waits in the one event loop for a transfer started by `start`, which sets `done` on completion.
// The loop running dry means no answer and no timeout can come any more (the io_context was
// stopped under us): that is the only failure made up here.
void wait_in_loop(can::CanBus& bus, const bool& done, std::error_code& ec) {
  if (!can::run_until(bus.context(), [&done] { return done; })) {
    ec = make_error_code(SdoAbort::general);
  }
}

}  // namespace

std::vector<std::uint8_t> SdoClient::upload(std::uint16_t index, std::uint8_t sub,
                                            std::error_code& ec) {
  ec.clear();
  auto done = std::make_shared<bool>(false);
  auto result = std::make_shared<std::pair<std::error_code, std::vector<std::uint8_t>>>();
  // The handler holds its own state: a handler exception may leave this frame before it runs.
  queue_upload(index, sub, [done, result](std::error_code e, std::vector<std::uint8_t> data) {
    *result = {e, std::move(data)};
    *done = true;
  });
  wait_in_loop(bus_, *done, ec);
  if (ec) return {};
  ec = result->first;
  return std::move(result->second);
}

std::vector<std::uint8_t> SdoClient::upload(std::uint16_t index, std::uint8_t sub) {
  std::error_code ec;
  auto data = upload(index, sub, ec);
  if (ec) throw SdoError(ec, node_, index, sub);
  return data;
}

void SdoClient::download(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> data,
                         std::error_code& ec) {
  ec.clear();
  auto done = std::make_shared<bool>(false);
  auto result = std::make_shared<std::error_code>();
  queue_download(index, sub, std::vector<std::uint8_t>(data.begin(), data.end()),
                 [done, result](std::error_code e) {
                   *result = e;
                   *done = true;
                 });
  wait_in_loop(bus_, *done, ec);
  if (!ec) ec = *result;
}

void SdoClient::download(std::uint16_t index, std::uint8_t sub,
                         std::span<const std::uint8_t> data) {
  std::error_code ec;
  download(index, sub, data, ec);
  if (ec) throw SdoError(ec, node_, index, sub);
}

}  // namespace wavebench::canopen
