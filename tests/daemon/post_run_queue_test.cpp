// The post-run queue and the stated progress alone (issue #21): one run at a time in order,
// drain() waits for all, the time left counts down between reports and never reaches zero
// while the work goes on.
#include "wavebench/daemon/post_run_queue.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "wavebench/daemon/stated_progress.hpp"

namespace wavebench::daemon {
namespace {

using namespace std::chrono_literals;

TEST(StatedProgress, CountsDownBetweenReports) {
  StatedProgress p;
  const auto t0 = StatedProgress::Clock::now();
  p.report(0.5, 10.0, t0);
  const auto later = p.at(t0 + 4s);
  EXPECT_NEAR(later.remaining_s, 6.0, 1e-9);
  EXPECT_GT(later.fraction, 0.5);
  EXPECT_LT(later.fraction, 1.0);
}

TEST(StatedProgress, OverdueSaysAboutASecondNotDone) {
  StatedProgress p;
  const auto t0 = StatedProgress::Clock::now();
  p.report(0.2, 3.0, t0);
  EXPECT_DOUBLE_EQ(p.at(t0 + 30s).remaining_s, 1.0);
  p.report(1.0, 0.0, t0);
  EXPECT_DOUBLE_EQ(p.at(t0 + 30s).remaining_s, 0.0);
  p.report(0.3, -1, t0);
  EXPECT_LT(p.at(t0 + 30s).remaining_s, 0);  // not known stays not known
}

RecordedLaunch job(const std::string& id, std::vector<std::string>& order, std::mutex& m,
                   std::chrono::milliseconds work) {
  return {id, "dynamic", "U1", 5.0, [id, &order, &m, work](const procedures::ProgressSink& progress) {
            if (progress) progress({id, "twin calibration", 0.5, 2.0});
            std::this_thread::sleep_for(work);
            {
              std::lock_guard lock(m);
              order.push_back(id);
            }
            procedures::RunOutcome outcome;
            outcome.run_id = id;
            return outcome;
          }};
}

TEST(PostRunQueue, OneAtATimeInOrderAndDrainWaitsForAll) {
  std::vector<std::string> order;
  std::mutex m;
  std::atomic<int> done{0};
  PostRunQueue queue([&](const std::string&, const procedures::RunOutcome* outcome, const std::string&) {
    EXPECT_NE(outcome, nullptr);
    ++done;
  });
  queue.push(job("a", order, m, 300ms));
  queue.push(job("b", order, m, 10ms));
  std::this_thread::sleep_for(100ms);
  const auto s = queue.status();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].run_id, "a");
  EXPECT_EQ(s[0].phase, "twin calibration");
  EXPECT_EQ(s[1].phase, "queued");
  // The second waits for the first: its time left includes the first's.
  EXPECT_GT(s[1].remaining_s, s[0].remaining_s);
  EXPECT_TRUE(queue.pending("b"));
  queue.drain();
  EXPECT_EQ(done.load(), 2);
  EXPECT_EQ(order, (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(queue.status().empty());
}

TEST(PostRunQueue, AFailingJobIsReportedAndTheNextStillRuns) {
  std::vector<std::string> errors;
  std::vector<std::string> order;
  std::mutex m;
  PostRunQueue queue([&](const std::string& id, const procedures::RunOutcome*, const std::string& e) {
    std::lock_guard lock(m);
    if (!e.empty()) errors.push_back(id + ": " + e);
  });
  queue.push({"x", "static", "U1", 1.0, [](const procedures::ProgressSink&) -> procedures::RunOutcome {
                throw std::runtime_error("disk gone");
              }});
  queue.push(job("y", order, m, 1ms));
  queue.drain();
  EXPECT_EQ(errors, (std::vector<std::string>{"x: disk gone"}));
  EXPECT_EQ(order, (std::vector<std::string>{"y"}));
}

}  // namespace
}  // namespace wavebench::daemon
