// One Modbus link per line (issue #9): the supervisor's heartbeats and polls and the bench's
// commands share one BrakeClient, so one connection; the safe-state write goes before the
// routine requests waiting for the link.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "brake_test_support.hpp"
#include "wavebench/modbus/brake_supervisor.hpp"
#include "wavebench/modbus/link_turns.hpp"

namespace wavebench::testing {
namespace {

using modbus::LinkTurns;
using modbus::TurnPriority;

class NullSink : public modbus::BrakeEventSink {
 public:
  void on_brake_event(const modbus::BrakeEvent&) noexcept override {}
};

TEST(LinkTurns, ASafetyTurnGoesBeforeTheRoutineTurnsWaiting) {
  LinkTurns turns;
  std::mutex mutex;
  std::vector<std::string> order;
  const auto record = [&](const std::string& who) {
    std::lock_guard lock(mutex);
    order.push_back(who);
  };
  std::optional<LinkTurns::Turn> on_the_wire;
  on_the_wire.emplace(turns.take(TurnPriority::routine));
  std::vector<std::thread> polls;
  for (int i = 0; i < 3; ++i) {
    polls.emplace_back([&] {
      const auto turn = turns.take(TurnPriority::routine);
      record("poll");
    });
  }
  ASSERT_TRUE(eventually([&] { return turns.waiting(TurnPriority::routine) == 3; }));
  std::thread safe([&] {
    const auto turn = turns.take(TurnPriority::safety);
    record("safe");
  });
  ASSERT_TRUE(eventually([&] { return turns.waiting(TurnPriority::safety) == 1; }));
  on_the_wire.reset();  // the transaction on the wire ends
  safe.join();
  for (auto& p : polls) p.join();
  ASSERT_EQ(order.size(), 4u);
  EXPECT_EQ(order.front(), "safe");
  EXPECT_EQ(turns.waiting(TurnPriority::routine), 0u);
}

TEST(LinkTurns, AThreadHoldingATurnTakesAnotherWithoutWaiting) {
  LinkTurns turns;
  std::optional<LinkTurns::Turn> outer;
  outer.emplace(turns.take(TurnPriority::safety));
  std::optional<LinkTurns::Turn> inner;
  inner.emplace(turns.take(TurnPriority::routine));  // would deadlock if not its own
  std::atomic<bool> other_got_it{false};
  std::thread other([&] {
    const auto turn = turns.take(TurnPriority::routine);
    other_got_it = true;
  });
  ASSERT_TRUE(eventually([&] { return turns.waiting(TurnPriority::routine) == 1; }));
  inner.reset();  // a nested turn releases nothing
  EXPECT_FALSE(other_got_it.load());
  EXPECT_EQ(turns.waiting(TurnPriority::routine), 1u);
  outer.reset();
  other.join();
  EXPECT_TRUE(other_got_it.load());
}

TEST(SharedBrakeLink, SupervisorAndCommandsUseOneConnection) {
  auto server = start_tcp_brake(/*real_time=*/true);
  modbus::BrakeClient client(client_config_tcp(server->port()));
  NullSink sink;
  modbus::BrakeSupervisor supervisor(client, sink);
  client.connect();
  supervisor.start();
  // Commands from this thread while the supervisor beats and polls on its own.
  for (int i = 0; i < 20; ++i) {
    client.set_setpoint(0.5 + 0.01 * i, modbus::BrakeMode::current, 0.0);
    client.enable();
  }
  ASSERT_TRUE(eventually([&] { return supervisor.heartbeats_sent() >= 10; }));
  ASSERT_TRUE(eventually([&] { return supervisor.latest().has_value(); }));
  EXPECT_TRUE(client.read().status.output_on);
  client.make_safe();
  EXPECT_FALSE(client.read().status.output_on);
  EXPECT_EQ(server->with_controller([](auto& c) { return c.holding()[1]; }),
            client.config().heartbeat.watchdog_timeout.count());  // armed by the supervisor
  supervisor.stop();
  EXPECT_EQ(server->connections_accepted(), 1u);
  EXPECT_EQ(server->most_clients_at_once(), 1u);
  EXPECT_EQ(client.connections(), 1u);
  EXPECT_EQ(supervisor.last_error(), "");
}

}  // namespace
}  // namespace wavebench::testing
