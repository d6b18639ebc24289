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
  const auto away = outbox.counts();
  EXPECT_GT(away.failures, 0u);
  EXPECT_EQ(away.pending, 1u);
  EXPECT_NE(away.last_error.find("fake store"), std::string::npos) << away.last_error;
  ASSERT_TRUE(away.next_attempt);  // waiting on a retry, at most retry_max away
  EXPECT_LE(*away.next_attempt - std::chrono::steady_clock::now(), std::chrono::milliseconds(20));
  EXPECT_TRUE(away.last_published_at.empty());
  server->down = false;
  ASSERT_TRUE(outbox.wait_idle(10s));
  const auto back = outbox.counts();
  EXPECT_FALSE(back.next_attempt);
  EXPECT_EQ(back.last_published_at.size(), 20u) << back.last_published_at;  // ISO 8601, UTC
  std::lock_guard lock(server->mutex);
  EXPECT_EQ(server->inserted["bench-a/" + id], 1);
}

// Each kind of store has its ledger: a bench that summarised its runs into its own store and
// then joins a shared one sends the shared one every run.
TEST(Outbox, AnotherLedgerSendsEveryRunAgain) {
  const auto dir = testing::fresh_dir("OutboxLedger");
  storage::RunStore store(dir, "test");
  const auto a = testing::add_synthetic_run(store, {});
  const auto b = testing::add_synthetic_run(store, {});
  auto own = std::make_shared<testing::FakeServer>();
  auto shared = std::make_shared<testing::FakeServer>();
  {
    auto options = quick("bench-a");
    options.ledger = "fleet_own_published";
    Outbox outbox(store, testing::fake_factory(own), options);
    EXPECT_EQ(outbox.counts().pending, 2u);
    outbox.start();
    ASSERT_TRUE(outbox.wait_idle(10s));
  }
  Outbox outbox(store, testing::fake_factory(shared), quick("bench-a"));
  EXPECT_EQ(outbox.counts().pending, 2u);
  outbox.start();
  ASSERT_TRUE(outbox.wait_idle(10s));
  {
    std::lock_guard lock(shared->mutex);
    EXPECT_EQ(shared->rows.size(), 2u);
    EXPECT_EQ(shared->rows.count("bench-a/" + a) + shared->rows.count("bench-a/" + b), 2u);
  }
  auto bad = quick("bench-a");
  bad.ledger = "runs; DROP TABLE runs";
  EXPECT_THROW(Outbox(store, testing::fake_factory(own), bad), std::invalid_argument);
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
