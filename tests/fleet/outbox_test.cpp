// The outbox against an in-memory store: every finished run sent exactly once, whether the
// store was away, the outbox restarted, or a run was handed to it twice.
#include "wavebench/fleet/outbox.hpp"

#include <gtest/gtest.h>

#include <chrono>

#include "fake_results_store.hpp"
#include "synthetic_runs.hpp"

namespace wavebench::fleet {
namespace {

using namespace std::chrono_literals;

OutboxOptions quick(const std::string& bench) {
  OutboxOptions o;
  o.identity = {bench, "line-1"};
  o.retry_first = 5ms;
  o.retry_max = 20ms;
  return o;
}

TEST(Outbox, SendsEachRunOnceEvenWhenHandedTwice) {
  const auto dir = testing::fresh_dir("OutboxTwice");
  storage::RunStore store(dir, "test");
  auto server = std::make_shared<testing::FakeServer>();
  Outbox outbox(store, testing::fake_factory(server), quick("bench-a"));
  outbox.start();
  const auto a = testing::add_synthetic_run(store, {});
  const auto b = testing::add_synthetic_run(store, {});
  outbox.enqueue(a);
  outbox.enqueue(b);
  outbox.enqueue(a);
  ASSERT_TRUE(outbox.wait_idle(10s));
  outbox.enqueue(a);  // after it was sent: published again, the store keeps one row
  ASSERT_TRUE(outbox.wait_idle(10s));
  std::lock_guard lock(server->mutex);
  ASSERT_EQ(server->rows.size(), 2u);
  EXPECT_EQ(server->inserted["bench-a/" + a], 1);
  EXPECT_EQ(server->inserted["bench-a/" + b], 1);
  EXPECT_EQ(server->rows["bench-a/" + a].station, "line-1");
  EXPECT_DOUBLE_EQ(server->rows["bench-a/" + b].figures.at("static_te_p2p"), 0.85);
}

TEST(Outbox, RunFinishedWhileTheStoreIsAwayArrivesWhenItReturns) {
  const auto dir = testing::fresh_dir("OutboxAway");
  storage::RunStore store(dir, "test");
  auto server = std::make_shared<testing::FakeServer>();
  server->down = true;
  Outbox outbox(store, testing::fake_factory(server), quick("bench-a"));
  outbox.start();
  const auto id = testing::add_synthetic_run(store, {});
  outbox.enqueue(id);
  EXPECT_FALSE(outbox.wait_idle(200ms));
  EXPECT_GT(outbox.counts().failures, 0u);
  EXPECT_EQ(outbox.counts().pending, 1u);
  server->down = false;
  ASSERT_TRUE(outbox.wait_idle(10s));
  std::lock_guard lock(server->mutex);
  EXPECT_EQ(server->inserted["bench-a/" + id], 1);
}

TEST(Outbox, WhatWasNotSentIsSentByTheNextStartAndNothingTwice) {
  const auto dir = testing::fresh_dir("OutboxRestart");
  auto server = std::make_shared<testing::FakeServer>();
  std::string sent, unsent, running;
  {
    storage::RunStore store(dir, "test");
    Outbox outbox(store, testing::fake_factory(server), quick("bench-a"));
    outbox.start();
    sent = testing::add_synthetic_run(store, {});
    outbox.enqueue(sent);
    ASSERT_TRUE(outbox.wait_idle(10s));
    server->down = true;
    unsent = testing::add_synthetic_run(store, {});
    outbox.enqueue(unsent);
    running = store.create_run("static", "U-9", "name: sim\n");
    outbox.enqueue(running);  // still running: nothing to send yet
    outbox.stop();
  }
  server->down = false;
  storage::RunStore store(dir, "test");  // marks `running` incomplete
  Outbox outbox(store, testing::fake_factory(server), quick("bench-a"));
  EXPECT_EQ(outbox.counts().pending, 2u);  // the unsent run and the incomplete one
  outbox.start();
  ASSERT_TRUE(outbox.wait_idle(10s));
  std::lock_guard lock(server->mutex);
  EXPECT_EQ(server->rows.size(), 3u);
  EXPECT_EQ(server->inserted["bench-a/" + sent], 1);
  EXPECT_EQ(server->inserted["bench-a/" + unsent], 1);
  EXPECT_EQ(server->rows["bench-a/" + running].status, "incomplete");
  EXPECT_EQ(server->publish_calls, 3);  // the sent run was not sent again
}

}  // namespace
}  // namespace wavebench::fleet
