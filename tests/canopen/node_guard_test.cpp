// Node guarding by the master (node_guard.hpp), pure logic on a hand-set steady clock: the
// request frame, alternating toggles, loss after the life time with no answer, a toggle that
// does not alternate, and a boot-up that restarts the toggle at 0.
#include "wavebench/canopen/node_guard.hpp"

#include <gtest/gtest.h>

namespace wavebench::canopen {
namespace {

using std::chrono::milliseconds;
using Clock = NodeGuard::Clock;

can::Frame answer(NodeId node, NmtState state, bool toggle) {
  return node_guard_response(node, state, toggle);
}

TEST(NodeGuard, RequestIsARemoteFrameOnTheErrorControlCobId) {
  const auto f = node_guard_request(5);
  EXPECT_EQ(f.id, 0x705U);
  EXPECT_TRUE(f.rtr);
  EXPECT_EQ(f.len, 1);
  EXPECT_EQ(can::to_string(f), "705#R1");
  const auto r = answer(5, NmtState::operational, true);
  EXPECT_EQ(can::to_string(r), "705#85");
  EXPECT_EQ(can::to_string(answer(5, NmtState::preoperational, false)), "705#7F");
}

TEST(NodeGuard, PollsEveryGuardTimeAndTakesAlternatingToggles) {
  NodeGuard g(3, milliseconds(100), milliseconds(300));
  const auto t0 = Clock::now();
  g.start(t0);
  EXPECT_TRUE(g.poll_due(t0));
  bool toggle = true;  // the first answer may carry either toggle
  for (int i = 0; i < 20; ++i) {
    const auto t = t0 + milliseconds(100 * i);
    ASSERT_TRUE(g.poll_due(t)) << i;
    g.polled(t);
    EXPECT_FALSE(g.poll_due(t + milliseconds(99)));
    EXPECT_EQ(g.on_frame(answer(3, NmtState::operational, toggle), t + milliseconds(1)),
              NodeGuard::Seen::answer)
        << i;
    toggle = !toggle;
    EXPECT_FALSE(g.lost(t + milliseconds(99)));
  }
  EXPECT_EQ(g.answers(), 20U);
  EXPECT_EQ(g.state(), NmtState::operational);
  EXPECT_EQ(g.on_frame(answer(4, NmtState::operational, toggle), t0), NodeGuard::Seen::none);
}

TEST(NodeGuard, LostWhenARequestStaysUnansweredForTheLifeTime) {
  NodeGuard g(3, milliseconds(100), milliseconds(300));
  const auto t0 = Clock::now();
  g.start(t0);
  g.polled(t0);
  g.on_frame(answer(3, NmtState::operational, false), t0 + milliseconds(2));
  // Silent from here on; the master keeps asking.
  for (int i = 1; i <= 3; ++i) g.polled(t0 + milliseconds(100 * i));
  EXPECT_FALSE(g.lost(t0 + milliseconds(400)));
  const auto lost = g.lost(t0 + milliseconds(401));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->why, NodeGuard::Lost::Why::silent);
  EXPECT_EQ(std::chrono::duration_cast<milliseconds>(lost->silence).count(), 399);
}

TEST(NodeGuard, AHeldLoopThatSentNoRequestIsNoLossByItself) {
  NodeGuard g(3, milliseconds(100), milliseconds(300));
  const auto t0 = Clock::now();
  g.start(t0);
  g.polled(t0);
  g.on_frame(answer(3, NmtState::operational, false), t0 + milliseconds(1));
  const auto late = t0 + milliseconds(2000);
  EXPECT_FALSE(g.lost(late));
  g.polled(late);
  EXPECT_EQ(g.on_frame(answer(3, NmtState::operational, true), late + milliseconds(1)),
            NodeGuard::Seen::answer);
  EXPECT_FALSE(g.lost(late + milliseconds(2)));
}

TEST(NodeGuard, AToggleThatDoesNotAlternateIsALoss) {
  NodeGuard g(3, milliseconds(100), milliseconds(300));
  const auto t0 = Clock::now();
  g.start(t0);
  g.polled(t0);
  EXPECT_EQ(g.on_frame(answer(3, NmtState::operational, false), t0), NodeGuard::Seen::answer);
  g.polled(t0 + milliseconds(100));
  EXPECT_EQ(g.on_frame(answer(3, NmtState::operational, false), t0 + milliseconds(101)),
            NodeGuard::Seen::toggle_error);
  const auto lost = g.lost(t0 + milliseconds(102));
  ASSERT_TRUE(lost);
  EXPECT_EQ(lost->why, NodeGuard::Lost::Why::toggle);
  EXPECT_EQ(g.toggle_errors(), 1U);
}

TEST(NodeGuard, ABootUpRestartsTheToggleAtZero) {
  NodeGuard g(3, milliseconds(100), milliseconds(300));
  const auto t0 = Clock::now();
  g.start(t0);
  g.polled(t0);
  g.on_frame(answer(3, NmtState::operational, true), t0);  // toggle 0 expected next
  EXPECT_EQ(g.on_frame(heartbeat_frame(3, NmtState::boot_up), t0 + milliseconds(50)),
            NodeGuard::Seen::boot_up);
  g.polled(t0 + milliseconds(100));
  EXPECT_EQ(g.on_frame(answer(3, NmtState::preoperational, false), t0 + milliseconds(101)),
            NodeGuard::Seen::answer);
  EXPECT_EQ(g.state(), NmtState::preoperational);
  // After a boot-up, toggle 1 first is an error.
  g.on_frame(heartbeat_frame(3, NmtState::boot_up), t0 + milliseconds(150));
  EXPECT_EQ(g.on_frame(answer(3, NmtState::preoperational, true), t0 + milliseconds(201)),
            NodeGuard::Seen::toggle_error);
}

TEST(NodeGuard, RefusesALifeTimeShorterThanTheGuardTime) {
  EXPECT_THROW(NodeGuard(3, milliseconds(100), milliseconds(50)), std::invalid_argument);
  EXPECT_THROW(NodeGuard(0, milliseconds(100), milliseconds(300)), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::canopen
