#pragma once
// The ResultsStore contract, one typed suite run over every implementation (PostgreSQL under
// label postgres, SQLite under unit): the same synthetic runs give the same answers — publish
// idempotent, runs filtered, limited and newest first, trends per bench, per pass and of the
// newest N, SPC equal to the hand-worked example of spc_test.cpp.
//
// A `Maker` has a default constructor that brings up an empty store and `make()` that opens a
// connection to it.

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "spc_hand_worked.hpp"
#include "synthetic_runs.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/results_store.hpp"

namespace wavebench::fleet::testing {

template <typename Maker>
class ResultsStoreContract : public ::testing::Test {
 protected:
  ResultsStoreContract()
      : local_dir_(fresh_dir(std::string("Contract") +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name())),
        local_(local_dir_, "test"),
        store_(maker_.make()) {}

  // A run in the bench's run store, published to the store under test as `bench`.
  std::string publish(const SyntheticRun& r, const std::string& bench,
                      storage::RunStatus status = storage::RunStatus::kComplete,
                      const std::string& verdict = "PASS") {
    const nlohmann::json limits = {{"static_p2p_arcmin", r.p2p_limit_arcmin}};
    const auto id = local_.create_run("static", r.unit, "name: sim\n", limits.dump(), "csf-25-100");
    local_.write_results(id, synthetic_results(id, r));
    local_.finish_run(id, status, "", verdict == "PASS", verdict);
    EXPECT_TRUE(store_->publish(
        summarise_run(*local_.find_run(id), synthetic_results(id, r), {bench, "line-1"})));
    ids_.push_back(id);
    return id;
  }
  static FigureQuery figure(const std::string& name,
                            const std::string& model = "CSF-25-100-2A-GR") {
    FigureQuery q;
    q.figure = name;
    q.gear_model = model;
    return q;
  }
  static std::vector<std::string> ids_of(const std::vector<FleetRunRow>& rows) {
    std::vector<std::string> ids;
    for (const auto& r : rows) ids.push_back(r.run_id);
    return ids;
  }
  static std::vector<double> values_of(const std::vector<TrendPoint>& points) {
    std::vector<double> values;
    for (const auto& p : points) values.push_back(p.value);
    return values;
  }

  std::filesystem::path local_dir_;
  storage::RunStore local_;
  Maker maker_;
  std::unique_ptr<ResultsStore> store_;
  std::vector<std::string> ids_;  // in publishing order: oldest first
};

TYPED_TEST_SUITE_P(ResultsStoreContract);

TYPED_TEST_P(ResultsStoreContract, PublishIsIdempotentAndKeepsTheRunsRow) {
  SyntheticRun r;
  r.p2p_forward_arcmin = 0.61;
  const auto id = this->publish(r, "bench-a");
  const auto again =
      summarise_run(*this->local_.find_run(id), synthetic_results(id, r), {"bench-a", "line-1"});
  EXPECT_FALSE(this->store_->publish(again));
  // Another connection sees the same single row.
  auto other = this->maker_.make();
  EXPECT_FALSE(other->publish(again));
  FleetRunQuery q;
  q.gear_model = "CSF-25-100-2A-GR";
  const std::vector<FleetRunRow> rows = other->runs(q);
  ASSERT_EQ(rows.size(), 1u);
  const FleetRunRow& row = rows[0];
  const auto local = *this->local_.find_run(id);
  EXPECT_EQ(row.bench, "bench-a");
  EXPECT_EQ(row.run_id, id);
  EXPECT_EQ(row.station, "line-1");
  EXPECT_EQ(row.operator_name, "ana");
  EXPECT_EQ(row.unit_serial, "U-0001");
  EXPECT_EQ(row.gear_model, "CSF-25-100-2A-GR");
  EXPECT_EQ(row.spec, "csf-25-100");
  EXPECT_EQ(row.spec_version.size(), 16u);
  EXPECT_EQ(row.procedure, "static");
  EXPECT_EQ(row.status, "complete");
  EXPECT_EQ(row.verdict, "PASS");
  EXPECT_EQ(row.started_at, local.started_at);
  EXPECT_EQ(row.finished_at, local.finished_at);
  EXPECT_EQ(row.software_version, "test");
  EXPECT_EQ(row.samples_ref, "bench-a:" + id + "/samples.wbs");
  EXPECT_DOUBLE_EQ(row.figures.at("static_te_p2p").get<double>(), 0.66);
  EXPECT_DOUBLE_EQ(row.figures.at("static_lost_motion").get<double>(), 0.4);
  EXPECT_FALSE(row.figures.contains("k1"));
  EXPECT_EQ(to_json(row)["operator"], "ana");
}

TYPED_TEST_P(ResultsStoreContract, RunsFilterLimitAndNewestFirst) {
  // Six runs, oldest first: benches a, b, a, b, a, b; run 3 failed, run 4 aborted, run 5 of
  // another gear model.
  for (int i = 0; i < 6; ++i) {
    SyntheticRun r;
    r.unit = "U-" + std::to_string(i);
    if (i == 5) r.model = "CSG-32-160";
    this->publish(r, i % 2 ? "bench-b" : "bench-a",
                  i == 4 ? storage::RunStatus::kAborted : storage::RunStatus::kComplete,
                  i == 3 ? "FAIL" : "PASS");
  }
  const auto& id = this->ids_;
  FleetRunQuery all;
  all.limit = 1000;
  EXPECT_EQ(this->ids_of(this->store_->runs(all)),
            (std::vector<std::string>{id[5], id[4], id[3], id[2], id[1], id[0]}));
  FleetRunQuery q = all;
  q.gear_model = "CSF-25-100-2A-GR";
  EXPECT_EQ(this->store_->runs(q).size(), 5u);
  q = all;
  q.bench = "bench-b";
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), (std::vector<std::string>{id[5], id[3], id[1]}));
  q = all;
  q.unit_serial = "U-2";
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), std::vector<std::string>{id[2]});
  q = all;
  q.verdict = "FAIL";
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), std::vector<std::string>{id[3]});
  q = all;
  q.status = "aborted";
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), std::vector<std::string>{id[4]});
  q = all;
  q.procedure = "dynamic";
  EXPECT_TRUE(this->store_->runs(q).empty());
  q = all;
  q.spec = "csf-25-100";
  EXPECT_EQ(this->store_->runs(q).size(), 6u);
  q = all;
  q.limit = 2;
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), (std::vector<std::string>{id[5], id[4]}));
  // from and to are inclusive bounds on the start time.
  q = all;
  q.from = this->local_.find_run(id[2])->started_at;
  q.to = this->local_.find_run(id[3])->started_at;
  EXPECT_EQ(this->ids_of(this->store_->runs(q)), (std::vector<std::string>{id[3], id[2]}));
  q = all;
  q.from = "2000-01-01";
  q.to = "2000-12-31T23:59:59Z";
  EXPECT_TRUE(this->store_->runs(q).empty());
  // An offset is a time like any other: one hour east of UTC, an hour later.
  const auto first = this->local_.find_run(id[0])->started_at;  // "...T10:15:00.123456Z"
  const int hour = std::stoi(first.substr(11, 2));
  if (hour < 23) {  // the same day an hour on, written with +01:00
    char shifted[64];
    std::snprintf(shifted, sizeof shifted, "%s%02d%s+01:00", first.substr(0, 11).c_str(), hour + 1,
                  first.substr(13, first.size() - 14).c_str());
    q = all;
    q.to = shifted;
    EXPECT_EQ(this->ids_of(this->store_->runs(q)), std::vector<std::string>{id[0]}) << shifted;
  }
  q = all;
  q.from = "yesterday";
  EXPECT_THROW(this->store_->runs(q), std::invalid_argument);
}

TYPED_TEST_P(ResultsStoreContract, TrendPerBenchPerPassAndTheNewestN) {
  for (int i = 0; i < 6; ++i) {
    SyntheticRun r;
    r.p2p_forward_arcmin = 0.5 + 0.01 * i;
    r.p2p_reverse_arcmin = 0.2 + 0.01 * i;
    this->publish(r, i % 2 ? "bench-b" : "bench-a");
  }
  SyntheticRun aborted;
  aborted.p2p_forward_arcmin = 9;
  this->publish(aborted, "bench-a", storage::RunStatus::kAborted, "FAIL");

  // The run's largest pass (forward at 60 N*m), complete runs only, oldest first.
  const auto all = this->store_->trend(this->figure("static_te_p2p"));
  ASSERT_EQ(all.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(all[static_cast<std::size_t>(i)].value, 0.55 + 0.01 * i, 1e-12);
    EXPECT_EQ(all[static_cast<std::size_t>(i)].sequence, i + 1);
    EXPECT_EQ(all[static_cast<std::size_t>(i)].run_id, this->ids_[static_cast<std::size_t>(i)]);
    EXPECT_EQ(all[static_cast<std::size_t>(i)].bench, i % 2 ? "bench-b" : "bench-a");
  }
  auto q = this->figure("static_te_p2p");
  q.bench = "bench-b";
  q.last = 2;
  const auto newest = this->store_->trend(q);
  ASSERT_EQ(newest.size(), 2u);
  EXPECT_NEAR(newest[0].value, 0.58, 1e-12);  // runs 3 and 5, oldest first
  EXPECT_NEAR(newest[1].value, 0.60, 1e-12);
  EXPECT_EQ(newest[0].sequence, 1);
  EXPECT_EQ(newest[1].run_id, this->ids_[5]);

  auto reverse = this->figure("static_te_p2p");
  reverse.direction = "reverse";
  reverse.load_nm = 0;
  const auto back = this->values_of(this->store_->trend(reverse));
  ASSERT_EQ(back.size(), 6u);
  EXPECT_NEAR(back[0], 0.20, 1e-12);
  EXPECT_NEAR(back[5], 0.25, 1e-12);
  auto loaded = this->figure("static_te_p2p");
  loaded.load_nm = 60;
  EXPECT_EQ(this->store_->trend(loaded).size(), 6u);  // forward, the only pass at 60 N*m
  loaded.direction = "reverse";
  EXPECT_TRUE(this->store_->trend(loaded).empty());

  auto lost = this->figure("static_lost_motion");
  lost.from = this->local_.find_run(this->ids_[4])->started_at;
  EXPECT_EQ(this->store_->trend(lost).size(), 2u);
  EXPECT_TRUE(this->store_->trend(this->figure("static_te_p2p", "CSG-32-160")).empty());
  EXPECT_TRUE(this->store_->trend(this->figure("k1")).empty());  // not measured
  auto bad = this->figure("k1");
  bad.direction = "forward";
  EXPECT_THROW(this->store_->trend(bad), std::invalid_argument);
  EXPECT_THROW(this->store_->trend(this->figure("nonsense")), std::invalid_argument);
  EXPECT_THROW(this->store_->trend(this->figure("static_te_p2p", "")), std::invalid_argument);
}

// The hand-worked example of spc_test.cpp (values 1, 2, 3, 5, 4) through the store.
TYPED_TEST_P(ResultsStoreContract, SpcEqualsTheHandWorkedExample) {
  for (const double v : {1.0, 2.0, 3.0, 5.0, 4.0}) {
    SyntheticRun r;
    r.p2p_forward_arcmin = v;
    r.p2p_reverse_arcmin = v - 0.5;
    r.p2p_limit_arcmin = 7.0;
    this->publish(r, "bench-a");
  }
  auto q = this->figure("static_te_p2p");
  q.direction = "forward";
  q.load_nm = 0;
  const auto given = this->store_->spc(q, {0.0, 7.0});
  EXPECT_EQ(this->values_of(given.points), (std::vector<double>{1, 2, 3, 5, 4}));
  EXPECT_EQ(given.limits_from, "command line");
  testing::expect_hand_worked_spc(given.figures);

  // Without limits given: the newest run's spec limit (an upper one), Cpk on that side only.
  const auto from_spec = this->store_->spc(q, {});
  ASSERT_TRUE(from_spec.limits.upper);
  EXPECT_DOUBLE_EQ(*from_spec.limits.upper, 7.0);
  EXPECT_FALSE(from_spec.limits.lower);
  EXPECT_EQ(from_spec.limits_from.rfind("spec csf-25-100 (", 0), 0u) << from_spec.limits_from;
  EXPECT_FALSE(from_spec.figures.cp);
  ASSERT_TRUE(from_spec.figures.cpk);
  EXPECT_NEAR(*from_spec.figures.cpk, 4 / (3 * 1.25 / 1.128), 1e-12);

  // A figure without a spec limit, and fewer than 2 points: no limits, no SPC.
  const auto lost = this->store_->spc(this->figure("k2"), {});
  EXPECT_EQ(lost.limits_from, "none");
  EXPECT_TRUE(lost.points.empty());
  EXPECT_EQ(to_json(lost)["spc"], nullptr);
  q.last = 1;
  EXPECT_EQ(to_json(this->store_->spc(q, {}))["spc"], nullptr);
}

// Every trend the figure declarations name (a newly declared one included, without an edit
// here) is a column the store writes, lists and trends.
TYPED_TEST_P(ResultsStoreContract, EveryDeclaredTrendIsStoredListedAndTrended) {
  SyntheticRun r;
  const nlohmann::json limits = {{"static_p2p_arcmin", r.p2p_limit_arcmin}};
  const auto id =
      this->local_.create_run("static", r.unit, "name: sim\n", limits.dump(), "csf-25-100");
  this->local_.write_results(id, synthetic_results(id, r));
  this->local_.finish_run(id, storage::RunStatus::kComplete, "", true, "PASS");
  auto summary =
      summarise_run(*this->local_.find_run(id), synthetic_results(id, r), {"bench-a", "line-1"});
  const auto& trends = fleet_figures();
  ASSERT_FALSE(trends.empty());
  for (std::size_t i = 0; i < trends.size(); ++i) summary.figures[trends[i].name] = 1.0 + i / 8.0;
  ASSERT_TRUE(this->store_->publish(summary));
  const auto rows = this->store_->runs(FleetRunQuery{});
  ASSERT_EQ(rows.size(), 1u);
  for (std::size_t i = 0; i < trends.size(); ++i) {
    SCOPED_TRACE(trends[i].name);
    ASSERT_TRUE(rows[0].figures.contains(trends[i].name));
    EXPECT_EQ(rows[0].figures[trends[i].name], nlohmann::json(1.0 + i / 8.0));
    const auto points = this->store_->trend(this->figure(trends[i].name));
    ASSERT_EQ(points.size(), 1u);
    EXPECT_EQ(points[0].value, 1.0 + i / 8.0);
  }
}

REGISTER_TYPED_TEST_SUITE_P(ResultsStoreContract, PublishIsIdempotentAndKeepsTheRunsRow,
                            RunsFilterLimitAndNewestFirst, TrendPerBenchPerPassAndTheNewestN,
                            SpcEqualsTheHandWorkedExample,
                            EveryDeclaredTrendIsStoredListedAndTrended);

}  // namespace wavebench::fleet::testing
