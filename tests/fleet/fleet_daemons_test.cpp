// Acceptance of issue #13 with the real daemon: two wavebenchd processes on the in-process
// simulated bench, each with its own runs folder, publishing to one PostgreSQL server at the same
// time: every run appears there exactly once with its results. And a daemon whose server is
// stopped mid-run: the run completes locally and arrives once the server is back.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <thread>

#include "daemon_process.hpp"
#include "daemon_runs.hpp"
#include "postgres_server.hpp"
#include "synthetic_runs.hpp"
#include "wavebench/daemon/daemon_client.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"

namespace wavebench::fleet {
namespace {

using namespace std::chrono_literals;
using daemon::DaemonClient;
using daemon::testing::DaemonProcess;

using testing::eventually;

constexpr const char* kToken = "fedcba9876543210fedcba9876543210";

class FleetDaemons : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<testing::PostgresServer>();
    server_->create_database("wavebench");
    dir_ = testing::fresh_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    token_ = dir_ / "token";
    std::ofstream(token_) << kToken << "\n";
    ::chmod(token_.c_str(), 0600);
  }

  // wavebenchd on the simulated bench, named `bench` in the fleet.
  std::unique_ptr<DaemonProcess> start_daemon(const std::string& bench) {
    const auto c = server_->config("wavebench", bench, "line-1");
    const auto results = dir_ / (bench + ".yaml");
    std::ofstream(results) << "results:\n  store: postgresql\n  url: '" << c.url
                           << "'\n  password_file: " << c.password_file.string()
                           << "\n  bench: " << bench << "\n  station: line-1\n"
                           << "  retry_max: 200 ms\n";
    auto p = std::make_unique<DaemonProcess>(
        std::vector<std::string>{WAVEBENCHD_PATH, "--config", "sim", "--runs",
                                 (dir_ / bench).string(), "--listen", "127.0.0.1:0", "--token-file",
                                 token_.string(), "--results", results.string()},
        dir_ / (bench + ".stderr.txt"));
    ports_[bench] = p->wait_for_port();
    return p;
  }
  DaemonClient client(const std::string& bench) {
    return {"http://127.0.0.1:" + std::to_string(ports_.at(bench)), kToken};
  }
  std::string run_to_the_end(const std::string& bench) {
    auto c = client(bench);
    return testing::run_to_the_end(c);
  }

  std::unique_ptr<testing::PostgresServer> server_;
  std::filesystem::path dir_, token_;
  std::map<std::string, int> ports_;
};

TEST_F(FleetDaemons, TwoDaemonsAtOnceEveryRunExactlyOnceWithItsResults) {
  constexpr int kRuns = 2;
  auto a = start_daemon("bench-a");
  auto b = start_daemon("bench-b");
  ASSERT_GT(ports_["bench-a"], 0) << a->stderr_text();
  ASSERT_GT(ports_["bench-b"], 0) << b->stderr_text();
  std::map<std::string, std::vector<std::string>> ids;
  const auto work = [&](const std::string& bench) {
    for (int i = 0; i < kRuns; ++i) ids[bench].push_back(run_to_the_end(bench));
  };
  ids["bench-a"];
  ids["bench-b"];
  std::thread ta([&] { work("bench-a"); });
  std::thread tb([&] { work("bench-b"); });
  ta.join();
  tb.join();

  const auto c = server_->config("wavebench");
  FleetRunQuery q;
  q.limit = 100;
  std::vector<FleetRunRow> rows;
  ASSERT_TRUE(eventually(
      [&] {
        rows = PostgresResultsStore(c).runs(q);
        return rows.size() >= 2u * kRuns;
      },
      60s))
      << rows.size() << " runs arrived\n"
      << a->stderr_text() << b->stderr_text();
  std::this_thread::sleep_for(500ms);  // anything sent twice would show now
  rows = PostgresResultsStore(c).runs(q);
  ASSERT_EQ(rows.size(), 2u * kRuns);
  std::set<std::string> seen;
  for (const auto& r : rows) {
    EXPECT_TRUE(seen.insert(r.bench + "/" + r.run_id).second) << "twice: " << r.run_id;
    const auto& mine = ids[r.bench];
    EXPECT_NE(std::find(mine.begin(), mine.end(), r.run_id), mine.end()) << r.run_id;
    EXPECT_EQ(r.status, "complete");
    EXPECT_EQ(r.gear_model, "Bench unit (seed 004)");
    EXPECT_EQ(r.station, "line-1");
    EXPECT_FALSE(r.verdict.empty());
    ASSERT_TRUE(r.figures.contains("static_te_p2p")) << r.figures.dump();
    // The same figure as the bench's own results.json.
    std::ifstream in(dir_ / r.bench / r.run_id / "results.json");
    const auto results = nlohmann::json::parse(in);
    double largest = 0;
    for (const auto& pass : results["static"]) {
      largest = std::max(largest, pass["p2p_arcmin"].get<double>());
    }
    EXPECT_DOUBLE_EQ(r.figures["static_te_p2p"].get<double>(), largest);
  }

  // The same store through a daemon's API.
  const auto spc = client("bench-a").get("/api/fleet/spc?figure=static_te_p2p&model=" +
                                         daemon::url_encode("Bench unit (seed 004)"));
  ASSERT_EQ(spc.status, 200) << spc.body.dump();
  EXPECT_EQ(spc.body["points"].size(), 2u * kRuns);
  EXPECT_DOUBLE_EQ(spc.body["limits"]["upper"].get<double>(), 7.0);  // sim-seed004's limit
  EXPECT_EQ(spc.body["spc"]["n"], 2 * kRuns);
  const auto bad = client("bench-b").get("/api/fleet/trend?figure=nonsense&model=x");
  EXPECT_EQ(bad.status, 400) << bad.body.dump();
  EXPECT_NE(bad.body.dump().find("nonsense"), std::string::npos);
}

TEST_F(FleetDaemons, ServerStoppedMidRunTheRunArrivesOnceAfterItReturns) {
  auto a = start_daemon("bench-a");
  ASSERT_GT(ports_["bench-a"], 0) << a->stderr_text();
  server_->stop();
  const auto id = run_to_the_end("bench-a");
  ASSERT_FALSE(id.empty());
  EXPECT_TRUE(std::filesystem::exists(dir_ / "bench-a" / id / "results.json"));
  // GET /api/status tells the run waits, why, and when the next attempt is.
  auto api = client("bench-a");
  nlohmann::json away;
  ASSERT_TRUE(eventually(
      [&] {
        away = api.get("/api/status").body.value("results_store", nlohmann::json());
        return away.is_object() && away["pending"].get<int>() >= 1 &&
               away["last_error"].is_string();
      },
      30s))
      << away.dump();
  EXPECT_EQ(away["kind"], "postgresql");
  EXPECT_TRUE(away["next_attempt_in_s"].is_number()) << away.dump();
  EXPECT_LE(away["next_attempt_in_s"].get<double>(), 0.2 + 1e-9);  // retry_max: 200 ms
  EXPECT_EQ(away.dump().find("wavebench-test-secret"), std::string::npos) << away.dump();

  server_->start();
  const auto c = server_->config("wavebench");
  FleetRunQuery q;
  ASSERT_TRUE(eventually(
      [&] {
        try {
          return PostgresResultsStore(c).runs(q).size() == 1;
        } catch (const std::exception&) {
          return false;
        }
      },
      60s))
      << a->stderr_text();
  nlohmann::json back;
  ASSERT_TRUE(eventually(
      [&] {
        back = api.get("/api/status").body.value("results_store", nlohmann::json());
        return back.is_object() && back["pending"] == 0;
      },
      30s))
      << back.dump();
  EXPECT_TRUE(back["last_published_at"].is_string()) << back.dump();
  EXPECT_TRUE(back["next_attempt_in_s"].is_null()) << back.dump();
  // Stopped and started again, the daemon sends nothing twice.
  a->signal(SIGTERM);
  a->wait();
  a = start_daemon("bench-a");
  ASSERT_GT(ports_["bench-a"], 0) << a->stderr_text();
  std::this_thread::sleep_for(1s);
  const auto rows = PostgresResultsStore(c).runs(q);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].run_id, id);
  EXPECT_NE(a->stderr_text().find("0 runs to send"), std::string::npos) << a->stderr_text();
}

}  // namespace
}  // namespace wavebench::fleet
