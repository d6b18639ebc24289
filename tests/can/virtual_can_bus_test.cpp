#include "wavebench/can/virtual_can_bus.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace wavebench::can {
namespace {

struct Recorder {
  std::vector<Frame> frames;
  std::vector<BusEventKind> events;
  CanBus::Subscription frame_sub;
  CanBus::Subscription event_sub;
  explicit Recorder(CanBus& bus)
      : frame_sub(bus.on_frame([this](const Frame& f) { frames.push_back(f); })),
        event_sub(bus.on_event([this](const BusEvent& e) { events.push_back(e.kind); })) {}
};

TEST(VirtualCanBus, EveryOtherEndpointSeesEachFrameInOrder) {
  boost::asio::io_context io;
  VirtualCanBus bus(io);
  auto a = bus.endpoint("a");
  auto b = bus.endpoint("b");
  auto c = bus.endpoint("c");
  Recorder ra(*a), rb(*b), rc(*c);
  a->send(Frame::make(0x100, {1}));
  b->send(Frame::make(0x200, {2}));
  a->send(Frame::make(0x101, {3}));
  EXPECT_TRUE(rb.frames.empty()) << "delivery only happens while the io_context runs";
  io.run();
  ASSERT_EQ(ra.frames.size(), 1U);
  EXPECT_EQ(ra.frames[0], Frame::make(0x200, {2}));
  ASSERT_EQ(rb.frames.size(), 2U);
  EXPECT_EQ(rb.frames[0], Frame::make(0x100, {1}));
  EXPECT_EQ(rb.frames[1], Frame::make(0x101, {3}));
  ASSERT_EQ(rc.frames.size(), 3U);
  EXPECT_EQ(rc.frames[1].id, 0x200U);
  EXPECT_NE(rc.frames[0].timestamp, std::chrono::system_clock::time_point{});
  EXPECT_EQ(bus.log().size(), 3U);
}

TEST(VirtualCanBus, FiltersMatchLikeCanRaw) {
  boost::asio::io_context io;
  VirtualCanBus bus(io);
  auto tx = bus.endpoint();
  auto rx = bus.endpoint();
  const FrameFilter only_sdo[] = {{0x580, 0x780, false}};
  rx->set_filters(only_sdo);
  Recorder r(*rx);
  tx->send(Frame::make(0x581, {}));
  tx->send(Frame::make(0x601, {}));
  tx->send(Frame::make(0x5FF, {}));
  tx->send(Frame::make(0x0581, {}));
  io.run();
  ASSERT_EQ(r.frames.size(), 3U);
  EXPECT_EQ(r.frames[1].id, 0x5FFU);

  const FrameFilter all_but_sync[] = {{0x080, kStandardIdMask | kExtendedFlag | kRtrFlag, true}};
  rx->set_filters(all_but_sync);
  r.frames.clear();
  tx->send(Frame::make(0x080, {}));
  tx->send(Frame::make(0x181, {}));
  io.run();
  io.restart();
  io.run();
  ASSERT_EQ(r.frames.size(), 1U);
  EXPECT_EQ(r.frames[0].id, 0x181U);

  rx->set_filters({});
  tx->send(Frame::make(0x181, {}));
  io.restart();
  io.run();
  EXPECT_EQ(r.frames.size(), 1U) << "an empty filter list receives nothing";
}

TEST(VirtualCanBus, UnsubscribingInsideAHandlerIsSafe) {
  boost::asio::io_context io;
  VirtualCanBus bus(io);
  auto tx = bus.endpoint();
  auto rx = bus.endpoint();
  int first = 0;
  int second = 0;
  CanBus::Subscription s1;
  CanBus::Subscription s2 = rx->on_frame([&](const Frame&) { ++second; });
  s1 = rx->on_frame([&](const Frame&) {
    ++first;
    s1.reset();
    s2.reset();
  });
  tx->send(Frame::make(0x1, {}));
  tx->send(Frame::make(0x2, {}));
  io.run();
  EXPECT_EQ(first, 1);
  EXPECT_EQ(second, 1) << "s2 was registered before s1 and ran in the first dispatch";
}

TEST(VirtualCanBus, RaisedEventsReachEveryEndpointAndBusOffBlocksSending) {
  boost::asio::io_context io;
  VirtualCanBus bus(io);
  auto a = bus.endpoint();
  auto b = bus.endpoint();
  Recorder ra(*a), rb(*b);
  bus.raise(BusEventKind::bus_off);
  io.run();
  ASSERT_EQ(ra.events.size(), 1U);
  EXPECT_EQ(ra.events[0], BusEventKind::bus_off);
  EXPECT_EQ(rb.events.size(), 1U);
  a->set_bus_off(true);
  std::error_code ec;
  a->send(Frame::make(0x100, {}), ec);
  EXPECT_EQ(ec, std::errc::network_down);
  EXPECT_THROW(a->send(Frame::make(0x100, {})), std::system_error);
}

TEST(VirtualCanBus, EndpointMayDieBeforeTheBusAndBusBeforeTheEndpoint) {
  boost::asio::io_context io;
  auto bus = std::make_unique<VirtualCanBus>(io);
  auto a = bus->endpoint();
  auto b = bus->endpoint();
  a->send(Frame::make(0x100, {}));
  b.reset();
  io.run();
  bus.reset();
  std::error_code ec;
  a->send(Frame::make(0x100, {}), ec);
  EXPECT_EQ(ec, std::errc::no_such_device);
}

}  // namespace
}  // namespace wavebench::can
