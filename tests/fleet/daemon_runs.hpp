#pragma once
// Short runs on a wavebenchd's simulated bench, for the fleet's daemon tests: start one through
// the API and wait until the daemon has finished it.

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "wavebench/daemon/daemon_client.hpp"

namespace wavebench::fleet::testing {

// A short static run on the simulated bench, judged against the simulated unit's spec.
inline const nlohmann::json kShortRun = {
    {"procedure", "static"},
    {"options",
     {{"positions", 4}, {"loads_nm", {0}}, {"move_speed_rad_s", 250}, {"window_s", 0.2}}},
    {"spec", "sim-seed004"},
    {"twin", false},
    {"report", false}};

// The simulated unit's gear model (sim-seed004's `model`).
inline constexpr const char* kSimModel = "Bench unit (seed 004)";

inline bool eventually(const std::function<bool()>& done,
                       std::chrono::seconds limit = std::chrono::seconds(180)) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return done();
}

// Starts kShortRun and waits until the daemon has finished it; its id (empty: not started).
inline std::string run_to_the_end(daemon::DaemonClient& c) {
  const auto started = c.post("/api/runs", kShortRun);
  EXPECT_EQ(started.status, 201) << started.body.dump();
  if (started.status != 201) return {};
  const auto id = started.body["run_id"].get<std::string>();
  EXPECT_TRUE(eventually([&] {
    const auto status = c.get("/api/status");
    const auto& last = status.body.value("last_run", nlohmann::json::object());
    return status.ok() && !status.body.value("run", nlohmann::json()).is_object() &&
           last.is_object() && last.value("id", "") == id;
  })) << c.get("/api/status").body.dump();
  return id;
}

}  // namespace wavebench::fleet::testing
