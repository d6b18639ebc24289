// The run history query: filters by unit, procedure, spec, verdict, status and id range, pages
// newest first with the total; an index written before the spec column keeps working.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include "test_dir.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::storage {
namespace {

std::vector<std::string> ids_of(const std::vector<RunRecord>& runs) {
  std::vector<std::string> out;
  for (const auto& r : runs) out.push_back(r.id);
  return out;
}

class RunHistory : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = testing::fresh_test_dir();
    store_ = std::make_unique<RunStore>(root_, "v");
    // 12 runs: units A/B alternating, static/dynamic by thirds, spec on even runs,
    // verdicts pass, fail, none in turn; the last one left running.
    for (int i = 0; i < 12; ++i) {
      const auto id = store_->create_run(i % 3 == 0 ? "dynamic" : "static", i % 2 ? "B" : "A",
                                         "cfg", "{}", i % 2 == 0 ? "csf-25-100" : "");
      ids_.push_back(id);
      if (i == 11) break;
      const std::optional<bool> verdict =
          i % 3 == 0 ? std::optional<bool>(true)
                     : (i % 3 == 1 ? std::optional<bool>(false) : std::nullopt);
      store_->finish_run(id, i == 5 ? RunStatus::kAborted : RunStatus::kComplete,
                         i == 5 ? "operator abort" : "", verdict);
    }
  }
  std::filesystem::path root_;
  std::unique_ptr<RunStore> store_;
  std::vector<std::string> ids_;  // oldest first
};

TEST_F(RunHistory, PagesAreNewestFirstAndTheTotalCountsEveryMatch) {
  RunQuery q;
  q.limit = 5;
  EXPECT_EQ(ids_of(store_->list_runs(q)),
            (std::vector<std::string>{ids_[11], ids_[10], ids_[9], ids_[8], ids_[7]}));
  EXPECT_EQ(store_->count_runs(q), 12u);
  q.offset = 10;
  EXPECT_EQ(ids_of(store_->list_runs(q)), (std::vector<std::string>{ids_[1], ids_[0]}));
  q.offset = 12;
  EXPECT_TRUE(store_->list_runs(q).empty());
  EXPECT_EQ(store_->count_runs(q), 12u);
}

TEST_F(RunHistory, AnUndecidedRunIsItsOwnVerdictWhateverItCountsAs) {
  // Undecided (a limit inside a figure's uncertainty interval), counted as a fail by its spec.
  const auto id = store_->create_run("static", "C", "cfg", "{}", "csf-25-100");
  store_->finish_run(id, RunStatus::kComplete, "", false, "UNDECIDED");
  const auto run = store_->find_run(id);
  ASSERT_TRUE(run);
  EXPECT_EQ(run->verdict, "UNDECIDED");
  EXPECT_EQ(run->pass, std::optional<bool>(false));
  EXPECT_EQ(to_json(*run)["verdict"], "UNDECIDED");
  EXPECT_EQ(to_json(*run)["pass"], false);
  RunQuery undecided;
  undecided.verdict = RunVerdict::kUndecided;
  EXPECT_EQ(ids_of(store_->list_runs(undecided)), std::vector<std::string>{id});
  RunQuery fail;
  fail.verdict = RunVerdict::kFail;
  fail.unit_serial = "C";
  EXPECT_TRUE(store_->list_runs(fail).empty());
  // Without a verdict string the verdict follows pass, as before.
  EXPECT_EQ(to_json(*store_->find_run(ids_[1]))["verdict"], "FAIL");
}

TEST_F(RunHistory, FiltersCombine) {
  RunQuery q;
  q.unit_serial = "A";
  q.procedure = "static";  // A: 0 2 4 6 8 10; static: not 0 3 6 9
  EXPECT_EQ(ids_of(store_->list_runs(q)),
            (std::vector<std::string>{ids_[10], ids_[8], ids_[4], ids_[2]}));
  EXPECT_EQ(store_->count_runs(q), 4u);
  RunQuery spec;
  spec.spec = "csf-25-100";
  EXPECT_EQ(store_->count_runs(spec), 6u);
  RunQuery no_spec;
  no_spec.spec = "";
  EXPECT_EQ(store_->count_runs(no_spec), 6u);
  RunQuery pass;
  pass.verdict = RunVerdict::kPass;  // 0 3 6 9
  EXPECT_EQ(ids_of(store_->list_runs(pass)),
            (std::vector<std::string>{ids_[9], ids_[6], ids_[3], ids_[0]}));
  RunQuery fail;
  fail.verdict = RunVerdict::kFail;  // 1 4 7 10
  EXPECT_EQ(store_->count_runs(fail), 4u);
  RunQuery none;
  none.verdict = RunVerdict::kNone;  // 2 5 8, and 11 still running
  EXPECT_EQ(store_->count_runs(none), 4u);
  RunQuery aborted;
  aborted.status = RunStatus::kAborted;
  EXPECT_EQ(ids_of(store_->list_runs(aborted)), (std::vector<std::string>{ids_[5]}));
  RunQuery range;
  range.from_id = ids_[3];
  range.to_id = ids_[6];
  EXPECT_EQ(ids_of(store_->list_runs(range)),
            (std::vector<std::string>{ids_[6], ids_[5], ids_[4], ids_[3]}));
  // A date prefix bounds by the day: every run here started today.
  RunQuery today;
  today.from_id = ids_[0].substr(0, 8);
  today.to_id = ids_[0].substr(0, 8) + "~";
  EXPECT_EQ(store_->count_runs(today), 12u);
  today.from_id = "2000";
  today.to_id = "2000~";
  EXPECT_EQ(store_->count_runs(today), 0u);
}

// The history's unit filter is a prefix; LIKE's own wildcards in it are characters.
TEST_F(RunHistory, AUnitPrefixFindsTheSerialsStartingWithItAndNoWildcardsInIt) {
  const auto a = store_->create_run("static", "0042-A", "cfg", "{}", "");
  const auto x = store_->create_run("static", "0042_X", "cfg", "{}", "");
  const auto p = store_->create_run("static", "0042%", "cfg", "{}", "");
  store_->create_run("static", "1042-A", "cfg", "{}", "");
  RunQuery q;
  q.unit_serial_prefix = "0042";
  EXPECT_EQ(ids_of(store_->list_runs(q)), (std::vector<std::string>{p, x, a}));
  q.unit_serial_prefix = "0042_";
  EXPECT_EQ(ids_of(store_->list_runs(q)), (std::vector<std::string>{x}));
  q.unit_serial_prefix = "0042%";
  EXPECT_EQ(ids_of(store_->list_runs(q)), (std::vector<std::string>{p}));
  q.unit_serial_prefix = "\\";
  EXPECT_TRUE(store_->list_runs(q).empty());
  q.unit_serial_prefix = "0042";
  EXPECT_EQ(store_->count_runs(q), 3U);
}

TEST_F(RunHistory, TheRecordCarriesSpecAndVerdict) {
  const auto first = to_json(*store_->find_run(ids_[0]));
  EXPECT_EQ(first["spec"], "csf-25-100");
  EXPECT_EQ(first["verdict"], "PASS");
  const auto second = to_json(*store_->find_run(ids_[1]));
  EXPECT_TRUE(second["spec"].is_null());
  EXPECT_EQ(second["verdict"], "FAIL");
  EXPECT_TRUE(to_json(*store_->find_run(ids_[2]))["verdict"].is_null());
}

// The index as the first release wrote it: no spec column, no history indexes.
constexpr const char* kFirstSchema = R"sql(
CREATE TABLE runs (
  id TEXT PRIMARY KEY, started_at TEXT NOT NULL, finished_at TEXT, unit_serial TEXT NOT NULL,
  procedure TEXT NOT NULL,
  status TEXT NOT NULL CHECK (status IN ('running','complete','aborted','incomplete')),
  reason TEXT NOT NULL DEFAULT '', pass INTEGER, limits_json TEXT NOT NULL DEFAULT '{}',
  software_version TEXT NOT NULL, config_hash TEXT NOT NULL);
INSERT INTO runs VALUES ('20250101T000000.000001Z', '2025-01-01T00:00:00.000001Z',
  '2025-01-01T00:10:00.000001Z', 'OLD-1', 'static', 'complete', '', 1, '{}', '0.1', 'abc');
)sql";

TEST(RunHistoryMigration, AnIndexWithoutTheSpecColumnIsMigratedAndKeepsItsRuns) {
  const auto root = testing::fresh_test_dir();
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((root / "index.sqlite").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, kFirstSchema, nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  for (int open = 0; open < 2; ++open) {  // migrating twice changes nothing
    RunStore store(root, "v2");
    const auto old = store.find_run("20250101T000000.000001Z");
    ASSERT_TRUE(old);
    EXPECT_EQ(old->unit_serial, "OLD-1");
    EXPECT_EQ(old->spec, "");
    EXPECT_EQ(old->pass, std::optional<bool>(true));
    RunQuery pass;
    pass.verdict = RunVerdict::kPass;
    EXPECT_EQ(store.count_runs(pass), 1u + open);
    store.create_run("dynamic", "NEW-1", "cfg", "{}", "sim-seed004");
    const auto runs = store.list_runs();
    ASSERT_EQ(runs.size(), 2u + open);
    EXPECT_EQ(runs[0].spec, "sim-seed004");
    // Mark it passed so that the second open counts it.
    store.finish_run(runs[0].id, RunStatus::kComplete, "", true);
  }
}

}  // namespace
}  // namespace wavebench::storage
