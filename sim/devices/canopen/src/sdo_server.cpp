#include "wavebench/simdevices/sdo_server.hpp"

#include <algorithm>

#include "wavebench/simdevices/sdo_abort.hpp"

namespace wavebench::simdevices {
namespace {

std::uint16_t index_of(const SdoPayload& p) {
  return static_cast<std::uint16_t>(p[1] | (p[2] << 8));
}

SdoPayload addressed(std::uint8_t command, std::uint16_t index, std::uint8_t sub) {
  return {command,
          static_cast<std::uint8_t>(index & 0xFF),
          static_cast<std::uint8_t>(index >> 8),
          sub,
          0,
          0,
          0,
          0};
}

}  // namespace

SdoPayload SdoServer::abort_payload(std::uint16_t index, std::uint8_t sub, std::uint32_t code) {
  SdoPayload p = addressed(0x80, index, sub);
  for (int i = 0; i < 4; ++i) p[4 + i] = static_cast<std::uint8_t>(code >> (8 * i));
  return p;
}

SdoPayload SdoServer::abort_transfer(std::uint32_t code) {
  state_ = State::kIdle;
  return abort_payload(index_, sub_, code);
}

std::optional<SdoPayload> SdoServer::handle(std::span<const std::uint8_t> request, double now) {
  SdoPayload req{};
  std::copy_n(request.begin(), std::min<std::size_t>(request.size(), 8), req.begin());
  last_activity_ = now;
  const unsigned ccs = req[0] >> 5;
  switch (ccs) {
    case 1:
      return initiate_download(req);
    case 0:
      if (state_ != State::kDownloading) return abort_payload(index_, sub_, sdo_abort::kBadCommand);
      return download_segment(req);
    case 2:
      return initiate_upload(req);
    case 3:
      if (state_ != State::kUploading) return abort_payload(index_, sub_, sdo_abort::kBadCommand);
      return upload_segment(req);
    case 4:  // abort from the client: drop the transfer silently
      state_ = State::kIdle;
      return std::nullopt;
    default:  // block transfers and reserved specifiers
      state_ = State::kIdle;
      return abort_payload(index_of(req), req[3], sdo_abort::kBadCommand);
  }
}

std::optional<SdoPayload> SdoServer::poll_timeout(double now) {
  if (state_ == State::kIdle || now - last_activity_ <= timeout_s_) return std::nullopt;
  return abort_transfer(sdo_abort::kTimeout);
}

SdoPayload SdoServer::initiate_download(const SdoPayload& req) {
  state_ = State::kIdle;
  index_ = index_of(req);
  sub_ = req[3];
  const bool expedited = req[0] & 0x02;
  const bool size_indicated = req[0] & 0x01;
  if (expedited) {
    std::size_t n = 4;
    if (size_indicated) {
      n = 4 - ((req[0] >> 2) & 0x03);
    } else if (const OdEntry* e = od_.find(index_, sub_)) {
      // Without a size the data is as long as the object (up to 4 bytes).
      const std::size_t fixed = data_type_size(e->type);
      if (fixed != 0 && fixed < 4) n = fixed;
    }
    const std::uint32_t abort = od_.write(index_, sub_, std::span(req).subspan(4, n));
    if (abort != 0) return abort_payload(index_, sub_, abort);
    return addressed(0x60, index_, sub_);
  }
  expected_size_.reset();
  if (size_indicated) {
    expected_size_ =
        static_cast<std::size_t>(from_le_bytes<std::uint32_t>(std::span(req).subspan(4)));
  }
  if (const std::uint32_t abort = od_.check_writable(index_, sub_, expected_size_); abort != 0) {
    return abort_payload(index_, sub_, abort);
  }
  buffer_.clear();
  toggle_ = false;
  state_ = State::kDownloading;
  return addressed(0x60, index_, sub_);
}

SdoPayload SdoServer::download_segment(const SdoPayload& req) {
  const bool toggle = req[0] & 0x10;
  if (toggle != toggle_) return abort_transfer(sdo_abort::kToggleBit);
  const std::size_t n = 7 - ((req[0] >> 1) & 0x07);
  buffer_.insert(buffer_.end(), req.begin() + 1, req.begin() + 1 + static_cast<std::ptrdiff_t>(n));
  const SdoPayload ack{
      static_cast<std::uint8_t>(0x20 | (toggle_ ? 0x10 : 0x00)), 0, 0, 0, 0, 0, 0, 0};
  toggle_ = !toggle_;
  if ((req[0] & 0x01) == 0) {
    if (expected_size_ && buffer_.size() > *expected_size_) {
      return abort_transfer(sdo_abort::kLengthMismatch);
    }
    return ack;
  }
  state_ = State::kIdle;
  if (expected_size_ && buffer_.size() != *expected_size_) {
    return abort_payload(index_, sub_, sdo_abort::kLengthMismatch);
  }
  const std::uint32_t abort = od_.write(index_, sub_, buffer_);
  if (abort != 0) return abort_payload(index_, sub_, abort);
  return ack;
}

SdoPayload SdoServer::initiate_upload(const SdoPayload& req) {
  state_ = State::kIdle;
  index_ = index_of(req);
  sub_ = req[3];
  std::vector<std::uint8_t> data;
  if (const std::uint32_t abort = od_.read(index_, sub_, data); abort != 0) {
    return abort_payload(index_, sub_, abort);
  }
  if (!data.empty() && data.size() <= 4) {
    SdoPayload resp =
        addressed(static_cast<std::uint8_t>(0x43 | ((4 - data.size()) << 2)), index_, sub_);
    std::copy(data.begin(), data.end(), resp.begin() + 4);
    return resp;
  }
  SdoPayload resp = addressed(0x41, index_, sub_);
  const auto size = static_cast<std::uint32_t>(data.size());
  for (int i = 0; i < 4; ++i) resp[4 + i] = static_cast<std::uint8_t>(size >> (8 * i));
  buffer_ = std::move(data);
  offset_ = 0;
  toggle_ = false;
  state_ = State::kUploading;
  return resp;
}

SdoPayload SdoServer::upload_segment(const SdoPayload& req) {
  const bool toggle = req[0] & 0x10;
  if (toggle != toggle_) return abort_transfer(sdo_abort::kToggleBit);
  const std::size_t n = std::min<std::size_t>(7, buffer_.size() - offset_);
  const bool last = offset_ + n == buffer_.size();
  SdoPayload resp{};
  resp[0] = static_cast<std::uint8_t>((toggle_ ? 0x10 : 0x00) | ((7 - n) << 1) | (last ? 1 : 0));
  std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(offset_), n, resp.begin() + 1);
  offset_ += n;
  toggle_ = !toggle_;
  if (last) state_ = State::kIdle;
  return resp;
}

}  // namespace wavebench::simdevices
