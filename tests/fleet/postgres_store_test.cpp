// The shared store on a real PostgreSQL 15 server (label postgres): migrations, idempotent
// publishing, the queries, and the acceptance cases of issue #13 — two benches writing at once,
// the server away mid-run, SPC against numpy on 50 runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <set>
#include <thread>

#include "postgres_server.hpp"
#include "synthetic_runs.hpp"
#include "wavebench/fleet/outbox.hpp"
#include "wavebench/fleet/postgres_results_store.hpp"

namespace wavebench::fleet {
namespace {

using namespace std::chrono_literals;
using testing::PostgresServer;

StoreFactory postgres(const ResultsConfig& config) {
  return [config]() -> std::unique_ptr<ResultsStore> {
    return std::make_unique<PostgresResultsStore>(config);
  };
}

FigureQuery figure(const std::string& name, const std::string& model) {
  FigureQuery q;
  q.figure = name;
  q.gear_model = model;
  return q;
}

OutboxOptions options_for(const ResultsConfig& c) {
  OutboxOptions o;
  o.identity = {c.bench, c.station};
  o.retry_first = 20ms;
  o.retry_max = 200ms;
  return o;
}

class PostgresStore : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = std::make_unique<PostgresServer>();
    server_->create_database("wavebench");
  }
  ResultsConfig config(const std::string& bench = "bench-a") const {
    return server_->config("wavebench", bench, "line-1");
  }
  std::unique_ptr<PostgresServer> server_;
};

TEST_F(PostgresStore, MigrationsApplyOnceAndAgainChangeNothing) {
  PostgresResultsStore first(config());
  EXPECT_EQ(first.schema_version(), fleet_schema_version());
  PostgresResultsStore second(config());
  EXPECT_EQ(second.schema_version(), fleet_schema_version());
  FleetRunQuery all;
  EXPECT_TRUE(second.runs(all).empty());
}

// A store written before a figure's trend was declared lacks its column: opening it adds the
// column (a step computed from the declarations), the old rows stay readable, new runs fill it.
TEST_F(PostgresStore, ANewlyDeclaredFigureColumnIsAddedToAnOldStore) {
  const auto dir = testing::fresh_dir("PgNewColumn");
  storage::RunStore local(dir, "test");
  testing::SyntheticRun synthetic;
  synthetic.lost_motion_arcmin = 0.41;
  const auto old_id = testing::add_synthetic_run(local, synthetic);
  {
    PostgresResultsStore store(config());
    ASSERT_TRUE(store.publish(summarise_run(
        *local.find_run(old_id), testing::synthetic_results(old_id, synthetic), {"bench-a", ""})));
  }
  server_->sql("wavebench", "ALTER TABLE fleet_runs DROP COLUMN static_lost_motion_arcmin");
  PostgresResultsStore store(config());
  EXPECT_EQ(store.schema_version(), fleet_schema_version());
  FleetRunQuery all;
  const auto rows = store.runs(all);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].run_id, old_id);
  EXPECT_FALSE(rows[0].figures.contains("static_lost_motion"));  // dropped with its column
  synthetic.lost_motion_arcmin = 0.43;
  const auto new_id = testing::add_synthetic_run(local, synthetic);
  ASSERT_TRUE(store.publish(summarise_run(
      *local.find_run(new_id), testing::synthetic_results(new_id, synthetic), {"bench-a", ""})));
  const auto points = store.trend(figure("static_lost_motion", synthetic.model));
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].run_id, new_id);
  EXPECT_DOUBLE_EQ(points[0].value, 0.43);
}

TEST_F(PostgresStore, PublishIsIdempotentAndKeepsTypedFigures) {
  const auto dir = testing::fresh_dir("PgPublish");
  storage::RunStore local(dir, "test");
  testing::SyntheticRun synthetic;
  synthetic.p2p_forward_arcmin = 0.61;
  const auto id = testing::add_synthetic_run(local, synthetic);
  const auto run = summarise_run(*local.find_run(id), testing::synthetic_results(id, synthetic),
                                 {"bench-a", "line-1"});
  PostgresResultsStore store(config());
  EXPECT_TRUE(store.publish(run));
  EXPECT_FALSE(store.publish(run));
  FleetRunQuery q;
  q.gear_model = "CSF-25-100-2A-GR";
  const auto rows = store.runs(q);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].bench, "bench-a");
  EXPECT_EQ(rows[0].run_id, id);
  EXPECT_EQ(rows[0].station, "line-1");
  EXPECT_EQ(rows[0].operator_name, "ana");
  EXPECT_EQ(rows[0].verdict, "PASS");
  EXPECT_EQ(rows[0].samples_ref, "bench-a:" + id + "/samples.wbs");
  EXPECT_EQ(rows[0].started_at, local.find_run(id)->started_at);
  EXPECT_DOUBLE_EQ(rows[0].figures["static_te_p2p"].get<double>(), 0.66);
  EXPECT_DOUBLE_EQ(rows[0].figures["static_lost_motion"].get<double>(), 0.4);
  EXPECT_FALSE(rows[0].figures.contains("k1"));

  auto one_pass = figure("static_te_p2p", "CSF-25-100-2A-GR");
  one_pass.direction = "forward";
  one_pass.load_nm = 0;
  const auto points = store.trend(one_pass);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_DOUBLE_EQ(points[0].value, 0.61);
}

TEST_F(PostgresStore, WrongPasswordIsRefusedWithTheServersMessage) {
  auto c = config();
  const auto pw = server_->dir() / "wrong.pw";
  std::ofstream(pw) << "not-the-password\n";
  ::chmod(pw.c_str(), 0600);
  c.password_file = pw;
  try {
    PostgresResultsStore store(c);
    FAIL() << "connected with a wrong password";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("password authentication failed"), std::string::npos)
        << e.what();
  }
}

// Acceptance: two benches, each with its own run folders, writing to one server at the same
// time: every run there exactly once with its results.
TEST_F(PostgresStore, TwoBenchesAtOnceEveryRunExactlyOnce) {
  constexpr int kRunsEach = 25;
  struct Bench {
    std::filesystem::path dir;
    std::vector<std::string> ids;
    std::vector<double> p2p;
  };
  Bench a{testing::fresh_dir("PgTwoA"), {}, {}}, b{testing::fresh_dir("PgTwoB"), {}, {}};
  const auto work = [&](Bench& bench, const std::string& name, double base) {
    storage::RunStore local(bench.dir, "test");
    Outbox outbox(local, postgres(config(name)), options_for(config(name)));
    outbox.start();
    for (int i = 0; i < kRunsEach; ++i) {
      testing::SyntheticRun r;
      r.unit = name + "-U" + std::to_string(i);
      r.p2p_forward_arcmin = base + 0.001 * i;
      bench.ids.push_back(testing::add_synthetic_run(local, r));
      bench.p2p.push_back(r.p2p_forward_arcmin + 0.05);
      outbox.enqueue(bench.ids.back());
    }
    ASSERT_TRUE(outbox.wait_idle(60s));
  };
  std::thread ta([&] { work(a, "bench-a", 0.5); });
  std::thread tb([&] { work(b, "bench-b", 0.7); });
  ta.join();
  tb.join();

  PostgresResultsStore store(config());
  FleetRunQuery all;
  all.limit = 1000;
  const auto rows = store.runs(all);
  ASSERT_EQ(rows.size(), 2u * kRunsEach);
  std::set<std::string> keys;
  for (const auto& r : rows) keys.insert(r.bench + "/" + r.run_id);
  EXPECT_EQ(keys.size(), rows.size());
  for (const auto* bench : {&a, &b}) {
    const std::string name = bench == &a ? "bench-a" : "bench-b";
    FleetRunQuery q;
    q.bench = name;
    q.limit = 1000;
    const auto mine = store.runs(q);
    ASSERT_EQ(mine.size(), static_cast<std::size_t>(kRunsEach));
    for (const auto& r : mine) {
      const auto at = std::find(bench->ids.begin(), bench->ids.end(), r.run_id);
      ASSERT_NE(at, bench->ids.end()) << r.run_id;
      EXPECT_NEAR(r.figures["static_te_p2p"].get<double>(),
                  bench->p2p[static_cast<std::size_t>(at - bench->ids.begin())], 1e-12);
    }
  }
}

// Acceptance: the server stops while a run goes on; the run completes locally and reaches the
// server after it returns, exactly once (also across a restart of the bench's outbox).
TEST_F(PostgresStore, ServerStoppedMidRunTheRunArrivesOnceAfterItReturns) {
  const auto dir = testing::fresh_dir("PgAway");
  storage::RunStore local(dir, "test");
  const auto c = config();
  std::string id;
  {
    Outbox outbox(local, postgres(c), options_for(c));
    outbox.start();
    const auto before = testing::add_synthetic_run(local, {});
    outbox.enqueue(before);
    ASSERT_TRUE(outbox.wait_idle(30s));

    const auto running = local.create_run("static", "U-AWAY", "name: sim\n", "{}", "csf-25-100");
    server_->stop();
    testing::SyntheticRun r;
    r.unit = "U-AWAY";
    local.write_results(running, testing::synthetic_results(running, r));
    local.finish_run(running, storage::RunStatus::kComplete, "", true, "PASS");
    id = running;
    outbox.enqueue(id);
    EXPECT_FALSE(outbox.wait_idle(500ms));
    EXPECT_GT(outbox.counts().failures, 0u);
    EXPECT_EQ(outbox.counts().pending, 1u);

    server_->start();
    ASSERT_TRUE(outbox.wait_idle(30s)) << outbox.counts().last_error;
  }
  Outbox again(local, postgres(c), options_for(c));
  EXPECT_EQ(again.counts().pending, 0u);

  PostgresResultsStore store(c);
  FleetRunQuery q;
  q.unit_serial = "U-AWAY";
  const auto rows = store.runs(q);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].run_id, id);
  EXPECT_EQ(rows[0].status, "complete");
  EXPECT_DOUBLE_EQ(rows[0].figures["static_te_p2p"].get<double>(), 0.85);
}

// Acceptance: SPC over 50 synthetic runs of known mean and sigma, against numpy.
TEST_F(PostgresStore, SpcOfFiftyRunsMatchesNumpy) {
  const auto dir = testing::fresh_dir("PgSpc");
  storage::RunStore local(dir, "test");
  PostgresResultsStore store(config());
  std::mt19937 rng(13);
  std::normal_distribution<double> p2p(0.80, 0.04);  // arcmin
  std::vector<double> values;
  for (int i = 0; i < 50; ++i) {
    testing::SyntheticRun r;
    r.unit = "U-" + std::to_string(1000 + i);
    r.p2p_forward_arcmin = p2p(rng);
    r.p2p_reverse_arcmin = r.p2p_forward_arcmin - 0.1;
    const auto id = testing::add_synthetic_run(local, r);
    store.publish(
        summarise_run(*local.find_run(id), testing::synthetic_results(id, r), {"bench-a", ""}));
    values.push_back(r.p2p_forward_arcmin);
  }
  auto q = figure("static_te_p2p", "CSF-25-100-2A-GR");
  q.direction = "forward";
  q.load_nm = 0;
  const auto answer = store.spc(q, {});
  ASSERT_EQ(answer.points.size(), 50u);
  for (std::size_t i = 0; i < values.size(); ++i) {
    ASSERT_DOUBLE_EQ(answer.points[i].value, values[i]) << "oldest first, in run order";
  }
  ASSERT_TRUE(answer.limits.upper);
  EXPECT_DOUBLE_EQ(*answer.limits.upper, 1.0);
  EXPECT_FALSE(answer.limits.lower);
  EXPECT_NE(answer.limits_from.find("csf-25-100"), std::string::npos) << answer.limits_from;

  // numpy, independently: mean, sample sigma, MR-bar, and the indices from them.
  const auto data = dir / "values.txt";
  {
    std::ofstream out(data);
    out.precision(17);
    for (double v : values) out << v << "\n";
  }
  const auto script = dir / "spc.py";
  std::ofstream(script) << "import numpy as np, sys\n"
                           "x = np.loadtxt(sys.argv[1])\n"
                           "m = x.mean(); s = x.std(ddof=1); mr = np.abs(np.diff(x)).mean()\n"
                           "sw = mr / 1.128; usl = 1.0\n"
                           "print(repr(m), repr(s), repr(mr), repr(m + 2.66 * mr), "
                           "repr(m - 2.66 * mr), repr((usl - m) / (3 * sw)), "
                           "repr((usl - m) / (3 * s)))\n";
  const std::string command = "/usr/bin/python3 " + script.string() + " " + data.string();
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  double mean = 0, sigma = 0, mr = 0, ucl = 0, lcl = 0, cpk = 0, ppk = 0;
  const int read =
      std::fscanf(pipe, "%lf %lf %lf %lf %lf %lf %lf", &mean, &sigma, &mr, &ucl, &lcl, &cpk, &ppk);
  ASSERT_EQ(::pclose(pipe), 0);
  ASSERT_EQ(read, 7);
  const auto& s = answer.figures;
  EXPECT_NEAR(s.mean, mean, 1e-12);
  EXPECT_NEAR(s.sigma, sigma, 1e-12);
  EXPECT_NEAR(s.mr_bar, mr, 1e-12);
  EXPECT_NEAR(s.ucl, ucl, 1e-12);
  EXPECT_NEAR(s.lcl, lcl, 1e-12);
  ASSERT_TRUE(s.cpk && s.ppk);
  EXPECT_NEAR(*s.cpk, cpk, 1e-9);
  EXPECT_NEAR(*s.ppk, ppk, 1e-9);
  EXPECT_FALSE(s.cp);  // one-sided spec
  // The known process: mean 0.80, sigma 0.04 (50 draws: within a few standard errors).
  EXPECT_NEAR(s.mean, 0.80, 3 * 0.04 / std::sqrt(50.0));
  EXPECT_NEAR(s.sigma, 0.04, 0.015);
}

TEST_F(PostgresStore, TrendFiltersByBenchAndTakesTheNewestN) {
  const auto dir = testing::fresh_dir("PgTrend");
  storage::RunStore local(dir, "test");
  PostgresResultsStore store(config());
  for (int i = 0; i < 6; ++i) {
    testing::SyntheticRun r;
    r.p2p_forward_arcmin = 0.5 + 0.01 * i;
    const auto id = testing::add_synthetic_run(local, r);
    store.publish(summarise_run(*local.find_run(id), testing::synthetic_results(id, r),
                                {i % 2 ? "bench-b" : "bench-a", ""}));
  }
  auto q = figure("static_te_p2p", "CSF-25-100-2A-GR");
  q.bench = "bench-b";
  q.last = 2;
  const auto points = store.trend(q);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_NEAR(points[0].value, 0.53 + 0.05, 1e-12);  // runs 3 and 5, oldest first
  EXPECT_NEAR(points[1].value, 0.55 + 0.05, 1e-12);
  EXPECT_EQ(points[0].sequence, 1);
  const auto other_model = figure("static_te_p2p", "CSG-32-160");
  EXPECT_TRUE(store.trend(other_model).empty());
  auto bad = figure("k1", "CSF-25-100-2A-GR");
  bad.direction = "forward";
  EXPECT_THROW(store.trend(bad), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::fleet
