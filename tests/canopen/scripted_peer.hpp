#pragma once
// A peer on the virtual bus that answers a fixed script: when the next expected frame arrives
// it sends its replies. Every frame it sees is recorded for byte-exact comparison.

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "wavebench/can/virtual_can_bus.hpp"

namespace wavebench::testing {

inline can::Frame F(const char* candump) {
  auto f = can::parse_frame(candump);
  if (!f) throw std::invalid_argument(std::string("bad frame literal ") + candump);
  return *f;
}

class ScriptedPeer {
 public:
  explicit ScriptedPeer(can::VirtualCanBus& bus) : endpoint_(bus.endpoint("peer")) {
    sub_ = endpoint_->on_frame([this](const can::Frame& f) { on_frame(f); });
  }
  void expect(const char* request, std::vector<const char*> replies = {}) {
    steps_.push_back({F(request), {}});
    for (auto* r : replies) steps_.back().replies.push_back(F(r));
  }
  void send(const char* frame) { endpoint_->send(F(frame)); }
  bool done() const { return steps_.empty(); }
  std::vector<std::string> received() const {
    std::vector<std::string> out;
    for (const auto& f : received_) out.push_back(can::to_string(f));
    return out;
  }
  can::VirtualCanEndpoint& endpoint() { return *endpoint_; }

 private:
  struct Step {
    can::Frame request;
    std::vector<can::Frame> replies;
  };
  void on_frame(const can::Frame& f) {
    received_.push_back(f);
    if (!steps_.empty() && steps_.front().request == f) {
      for (const auto& r : steps_.front().replies) endpoint_->send(r);
      steps_.pop_front();
    }
  }
  std::unique_ptr<can::VirtualCanEndpoint> endpoint_;
  can::CanBus::Subscription sub_;
  std::deque<Step> steps_;
  std::vector<can::Frame> received_;
};

}  // namespace wavebench::testing
