// Over-limit starts through wavebenchd on the in-process simulated bench (issue #8): each gets
// 400 naming the key, no run folder and no index row appear, and the bench does not move —
// the input angle in the live stream (the drive's position feedback, read off the bus every
// SYNC) stays where it was while the daemon keeps acquiring.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon_process.hpp"
#include "test_dir.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon::testing {
namespace {

namespace fs = std::filesystem;
constexpr const char* kTokenText = "0123456789abcdef0123456789abcdef";

struct LiveAngle {
  std::uint64_t seq = 0;
  double theta_in_rad = NAN;
};

// The newest live sample with a valid input angle.
LiveAngle newest_angle(const DaemonClient& client) {
  const auto reply = client.get("/api/live?since=0&limit=100000");
  LiveAngle a;
  if (!reply.ok()) return a;
  for (const auto& s : reply.body["samples"]) {
    if (s["theta_in_rad"].is_number()) a = {s["seq"].get<std::uint64_t>(), s["theta_in_rad"]};
  }
  return a;
}

TEST(HostileDaemonLimits, OverLimitStartsAre400AndNothingIsCreatedOrMoves) {
  const auto dir = fresh_test_dir();
  const auto runs = dir / "runs";
  std::ofstream(dir / "token") << kTokenText << "\n";
  ::chmod((dir / "token").c_str(), 0600);
  DaemonProcess p({WAVEBENCHD_PATH, "--config", "sim", "--runs", runs.string(), "--listen",
                   "127.0.0.1:0", "--token-file", (dir / "token").string()},
                  dir / "stderr.txt");
  const int port = p.wait_for_port();
  ASSERT_GT(port, 0) << p.stderr_text();
  const DaemonClient client("http://127.0.0.1:" + std::to_string(port), kTokenText);

  // Acquisition is running before anything is asked of the bench.
  LiveAngle before;
  for (int i = 0; i < 600 && before.seq < 20; ++i) {
    before = newest_angle(client);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_GE(before.seq, 20u) << "no live samples from the idle bench";

  struct Start {
    nlohmann::json body;
    std::string key;
  };
  std::vector<nlohmann::json> many_loads(100000, 10.0);
  const std::vector<Start> starts = {
      {{{"procedure", "static"}, {"options", {{"positions", 2}, {"loads_nm", {0, 200}}}}},
       "static.loads_nm[1]"},
      // Refused while parsing, before any option is read: more values than a request needs.
      {{{"procedure", "static"}, {"options", {{"loads_nm", many_loads}}}}, "body"},
      {{{"procedure", "static"}, {"options", {{"loads_nm", std::vector<double>(100, 10.0)}}}},
       "static.loads_nm"},
      {{{"procedure", "static"}, {"options", {{"move_speed_rad_s", 400}}}},
       "static.move_speed_rad_s"},
      {{{"procedure", "dynamic"}, {"options", {{"input_rpm", 4000}}}}, "dynamic.input_rpm"},
      {{{"procedure", "dynamic"}, {"options", {{"load_nm", 120}}}}, "dynamic.load_nm"},
      {{{"procedure", "dynamic"}, {"options", {{"output_revolutions", 1000}}}}, "dynamic"},
      {{{"procedure", "lost-motion"}, {"options", {{"torques_nm", {10, 20, 30, 1000}}}}},
       "lost-motion.torques_nm[3]"},
      {{{"procedure", "static"}, {"options", {{"positions", 3600}, {"window_s", 600}}}}, "static"},
  };
  int refused = 0;
  for (const auto& s : starts) {
    const auto reply = client.post("/api/runs", s.body);
    EXPECT_EQ(reply.status, 400) << s.key << ": " << reply.body.dump().substr(0, 300);
    EXPECT_NE(reply.body.value("detail", "").find(s.key), std::string::npos)
        << reply.body.value("detail", "");
    refused += reply.status == 400 ? 1 : 0;
  }

  // Nothing was created: no run folder beside the store's own files and the logs, no index row.
  std::vector<std::string> entries;
  for (const auto& e : fs::directory_iterator(runs)) entries.push_back(e.path().filename());
  for (const auto& name : entries) {
    EXPECT_TRUE(name == storage::kRunIndexFile || name.rfind("index.sqlite-", 0) == 0 ||
                name == storage::kWriterLockFile || name == "logs")
        << "created: " << name;
  }
  const auto listed = client.get("/api/runs");
  ASSERT_TRUE(listed.ok());
  EXPECT_TRUE(listed.body["runs"].empty()) << listed.body.dump();

  // Nothing moved: later samples, same input angle. The idle drive's power stage is off, so the
  // shaft is free and may settle by a few milliradians (gear friction and twist relaxing); the
  // 628 rad the probe saw, or one input turn, would be far outside this.
  LiveAngle after;
  for (int i = 0; i < 600 && after.seq < before.seq + 20; ++i) {
    after = newest_angle(client);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_GE(after.seq, before.seq + 20) << "acquisition stopped";
  EXPECT_NEAR(after.theta_in_rad, before.theta_in_rad, 2e-2);
  const auto status = client.get("/api/status");
  EXPECT_EQ(status.body.value("state", ""), "ready") << status.body.dump();
  std::printf(
      "[ hostile  ] %zu over-limit starts through wavebenchd, %d refused with 400; input "
      "angle %.6f -> %.6f rad over %llu live samples\n",
      starts.size(), refused, before.theta_in_rad, after.theta_in_rad,
      static_cast<unsigned long long>(after.seq - before.seq));
  p.signal(SIGTERM);
  const int wait_status = p.wait();
  EXPECT_TRUE(WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0) << p.stderr_text();
}

}  // namespace
}  // namespace wavebench::daemon::testing
