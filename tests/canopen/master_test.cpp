#include "wavebench/canopen/master.hpp"

#include <gtest/gtest.h>

#include "scripted_peer.hpp"

namespace wavebench::canopen {
namespace {

using testing::ScriptedPeer;

// Runs until the heartbeat consumer of node 3 has timed out (guard: 10 s).
bool run_until_lost(boost::asio::io_context& io, Master& master) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!master.heartbeat(3)->timed_out() && std::chrono::steady_clock::now() < end) {
    io.restart();
    io.run_one_for(std::chrono::milliseconds(10));
  }
  return master.heartbeat(3)->timed_out();
}

TEST(Master, RoutesPdosEmcyHeartbeatsAndBusEvents) {
  boost::asio::io_context io;
  can::VirtualCanBus bus(io);
  auto ep = bus.endpoint("master");
  ScriptedPeer node(bus);
  std::vector<std::string> log;
  Master master(
      *ep,
      Master::Hooks{[&](NodeId n, NmtState s) noexcept {
                      log.push_back("state " + std::to_string(n) + " " + std::string(to_string(s)));
                    },
                    [&](NodeId n) noexcept { log.push_back("lost " + std::to_string(n)); }, nullptr,
                    [&](const Emergency& e) noexcept {
                      log.push_back("emcy " + describe_emcy_code(e.error_code));
                    },
                    [&](const can::BusEvent& e) noexcept {
                      log.push_back("bus " + std::string(can::to_string(e.kind)));
                    }});
  std::vector<std::string> pdos;
  master.on_pdo(0x183, [&](const can::Frame& f) { pdos.push_back(can::to_string(f)); });
  master.consume_heartbeat(3, std::chrono::milliseconds(30));
  node.send("183#01020304");
  node.send("283#05");
  node.send("703#05");
  node.send("083#1023010000000000");
  bus.raise(can::BusEventKind::bus_off);
  io.run_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(run_until_lost(io, master));
  EXPECT_EQ(pdos, std::vector<std::string>{"183#01020304"});
  EXPECT_EQ(log, (std::vector<std::string>{"state 3 operational", "emcy 2310 current",
                                           "bus bus-off", "lost 3"}));
}

}  // namespace
}  // namespace wavebench::canopen
