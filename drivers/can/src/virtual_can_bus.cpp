#include "wavebench/can/virtual_can_bus.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

namespace wavebench::can {

VirtualCanBus::VirtualCanBus(boost::asio::io_context& io)
    : io_(io), endpoints_(std::make_shared<std::vector<VirtualCanEndpoint*>>()) {}

VirtualCanBus::~VirtualCanBus() {
  for (auto* ep : *endpoints_) ep->bus_ = nullptr;
  endpoints_->clear();
}

std::unique_ptr<VirtualCanEndpoint> VirtualCanBus::endpoint(std::string name) {
  std::unique_ptr<VirtualCanEndpoint> ep(new VirtualCanEndpoint(*this, std::move(name)));
  endpoints_->push_back(ep.get());
  return ep;
}

void VirtualCanBus::raise(BusEventKind kind) {
  std::weak_ptr<std::vector<VirtualCanEndpoint*>> weak = endpoints_;
  boost::asio::post(io_, [weak, kind] {
    auto eps = weak.lock();
    if (!eps) return;
    const auto snapshot = *eps;
    for (auto* ep : snapshot) {
      if (std::find(eps->begin(), eps->end(), ep) == eps->end()) continue;
      ep->notify(BusEvent{kind, {}});
    }
  });
}

void VirtualCanBus::transmit(const VirtualCanEndpoint* from, const Frame& frame) {
  if (recording_) log_.push_back(frame);
  std::weak_ptr<std::vector<VirtualCanEndpoint*>> weak = endpoints_;
  // One posted handler per frame keeps delivery in send order and lets the receiver's reply be
  // queued behind frames already in flight, as on a real bus.
  boost::asio::post(io_, [weak, from, frame = Frame(frame)]() mutable {
    auto eps = weak.lock();
    if (!eps) return;
    if (frame.timestamp.time_since_epoch().count() == 0)
      frame.timestamp = std::chrono::system_clock::now();
    const auto snapshot = *eps;
    for (auto* ep : snapshot) {
      if (ep == from) continue;
      // An endpoint destroyed by an earlier handler in this loop is gone from the live list.
      if (std::find(eps->begin(), eps->end(), ep) == eps->end()) continue;
      ep->receive(frame);
    }
  });
}

void VirtualCanBus::detach(VirtualCanEndpoint* endpoint) noexcept {
  auto& eps = *endpoints_;
  eps.erase(std::remove(eps.begin(), eps.end(), endpoint), eps.end());
}

VirtualCanEndpoint::VirtualCanEndpoint(VirtualCanBus& bus, std::string name)
    : bus_(&bus), name_(std::move(name)), filters_{FrameFilter{}} {}

VirtualCanEndpoint::~VirtualCanEndpoint() {
  if (bus_ != nullptr) bus_->detach(this);
}

void VirtualCanEndpoint::send(const Frame& frame, std::error_code& ec) noexcept {
  ec.clear();
  if (bus_ == nullptr) {
    ec = std::make_error_code(std::errc::no_such_device);
    return;
  }
  if (bus_off_) {
    ec = std::make_error_code(std::errc::network_down);
    return;
  }
  if (frame.len > kMaxDataLength || frame.error) {
    ec = std::make_error_code(std::errc::invalid_argument);
    return;
  }
  try {
    bus_->transmit(this, frame);
  } catch (...) {
    ec = std::make_error_code(std::errc::not_enough_memory);
  }
}

void VirtualCanEndpoint::set_filters(std::span<const FrameFilter> filters) {
  filters_.assign(filters.begin(), filters.end());
}

void VirtualCanEndpoint::receive(const Frame& frame) noexcept {
  const bool pass = std::any_of(filters_.begin(), filters_.end(),
                                [&](const FrameFilter& f) { return f.matches(frame); });
  if (pass) deliver(frame);
}

}  // namespace wavebench::can
