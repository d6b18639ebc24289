#pragma once
// A minimal SDO server written for the tests, independent of the client under test: expedited
// upload/download and segmented upload over a map of objects, plus hooks on writes. Enough to
// stand in for a device whose behaviour a test scripts (a CiA 402 state machine, an encoder).

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "wavebench/can/virtual_can_bus.hpp"

namespace wavebench::testing {

class FakeSdoServer {
 public:
  using Bytes = std::vector<std::uint8_t>;
  FakeSdoServer(can::VirtualCanBus& bus, std::uint8_t node)
      : node_(node), endpoint_(bus.endpoint("fake-server")) {
    sub_ = endpoint_->on_frame([this](const can::Frame& f) {
      if (f.id == 0x600U + node_ && f.len == 8) handle(f);
    });
  }
  template <typename T>
  void set(std::uint16_t index, std::uint8_t sub, T value) {
    Bytes b(sizeof(T));
    std::memcpy(b.data(), &value, sizeof(T));
    objects_[key(index, sub)] = b;
  }
  void set_bytes(std::uint16_t index, std::uint8_t sub, Bytes b) {
    objects_[key(index, sub)] = std::move(b);
  }
  template <typename T>
  T get(std::uint16_t index, std::uint8_t sub) const {
    T v{};
    const auto& b = objects_.at(key(index, sub));
    std::memcpy(&v, b.data(), sizeof(T));
    return v;
  }
  bool has(std::uint16_t index, std::uint8_t sub) const {
    return objects_.count(key(index, sub)) != 0;
  }
  // Called after a successful download; may change other objects.
  std::function<void(std::uint16_t, std::uint8_t, const Bytes&)> on_write;
  // Called before each download; a non-zero SDO abort code refuses it (a read-only object).
  std::function<std::uint32_t(std::uint16_t, std::uint8_t)> refuse_write;
  // Called before each upload (to let a simulated device advance).
  std::function<void(std::uint16_t, std::uint8_t)> on_read;
  std::vector<std::pair<std::uint32_t, Bytes>> writes;  // every download, in order
  bool silent = false;

 private:
  static std::uint32_t key(std::uint16_t index, std::uint8_t sub) {
    return static_cast<std::uint32_t>(index) << 8 | sub;
  }
  void reply(std::initializer_list<std::uint8_t> head, std::uint16_t index, std::uint8_t sub,
             const std::uint8_t* tail = nullptr, std::size_t n = 0) {
    can::Frame f;
    f.id = 0x580U + node_;
    f.len = 8;
    f.data[0] = *head.begin();
    f.data[1] = static_cast<std::uint8_t>(index);
    f.data[2] = static_cast<std::uint8_t>(index >> 8);
    f.data[3] = sub;
    for (std::size_t i = 0; i < n; ++i) f.data[4 + i] = tail[i];
    endpoint_->send(f);
  }
  void abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code) {
    std::uint8_t c[4];
    std::memcpy(c, &code, 4);
    reply({0x80}, index, sub, c, 4);
  }
  void handle(const can::Frame& f) {
    if (silent) return;
    const std::uint8_t cmd = f.data[0];
    if ((cmd & 0xE0) == 0x60 && segmented_) {  // upload segment request
      can::Frame r;
      r.id = 0x580U + node_;
      r.len = 8;
      const std::size_t n = std::min<std::size_t>(7, pending_.size() - offset_);
      const bool last = offset_ + n == pending_.size();
      r.data[0] = static_cast<std::uint8_t>((cmd & 0x10) | ((7 - n) << 1) | (last ? 1 : 0));
      std::memcpy(&r.data[1], pending_.data() + offset_, n);
      offset_ += n;
      if (last) segmented_ = false;
      endpoint_->send(r);
      return;
    }
    const auto index = static_cast<std::uint16_t>(f.data[1] | f.data[2] << 8);
    const std::uint8_t sub = f.data[3];
    if (cmd == 0x80) return;
    if (cmd == 0x40) {
      if (on_read) on_read(index, sub);
      auto it = objects_.find(key(index, sub));
      if (it == objects_.end()) return abort(index, sub, 0x06020000);
      const auto& b = it->second;
      if (b.size() <= 4 && !b.empty()) {
        reply({static_cast<std::uint8_t>(0x43 | ((4 - b.size()) << 2))}, index, sub, b.data(),
              b.size());
      } else {
        const auto size = static_cast<std::uint32_t>(b.size());
        std::uint8_t s[4];
        std::memcpy(s, &size, 4);
        reply({0x41}, index, sub, s, 4);
        pending_ = b;
        offset_ = 0;
        segmented_ = true;
      }
      return;
    }
    if ((cmd & 0xE3) == 0x23) {  // expedited download with size
      const std::size_t n = 4 - ((cmd >> 2) & 3);
      Bytes b(f.data.begin() + 4, f.data.begin() + 4 + static_cast<long>(n));
      auto it = objects_.find(key(index, sub));
      if (it == objects_.end()) return abort(index, sub, 0x06020000);
      if (it->second.size() != n) return abort(index, sub, 0x06070010);
      if (refuse_write) {
        if (const std::uint32_t code = refuse_write(index, sub); code != 0)
          return abort(index, sub, code);
      }
      it->second = b;
      writes.emplace_back(key(index, sub), b);
      reply({0x60}, index, sub);
      if (on_write) on_write(index, sub, b);
      return;
    }
    abort(index, sub, 0x05040001);
  }

  std::uint8_t node_;
  std::unique_ptr<can::VirtualCanEndpoint> endpoint_;
  can::CanBus::Subscription sub_;
  std::map<std::uint32_t, Bytes> objects_;
  Bytes pending_;
  std::size_t offset_ = 0;
  bool segmented_ = false;
};

}  // namespace wavebench::testing
