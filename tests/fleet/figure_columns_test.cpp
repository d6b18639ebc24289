// The SQLite store's figure columns come from the figure declarations (issue #23): a store
// written before a figure's trend was declared lacks its column; read-only it reads as absent,
// opened for writing the column is added, the old rows stay readable and new runs fill it.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <set>

#include "synthetic_runs.hpp"
#include "wavebench/fleet/fleet_figures.hpp"
#include "wavebench/fleet/run_summary.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"

namespace wavebench::fleet {
namespace {

std::set<std::string> columns_of(const std::filesystem::path& file) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "SELECT name FROM pragma_table_info('fleet_runs')", -1, &s, nullptr);
  std::set<std::string> out;
  while (sqlite3_step(s) == SQLITE_ROW) {
    out.insert(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)));
  }
  sqlite3_finalize(s);
  sqlite3_close(db);
  return out;
}

void exec(const std::filesystem::path& file, const char* sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* message = nullptr;
  const int rc = sqlite3_exec(db, sql, nullptr, nullptr, &message);
  EXPECT_EQ(rc, SQLITE_OK) << (message ? message : "");
  sqlite3_free(message);
  sqlite3_close(db);
}

FigureQuery figure(const std::string& name, const std::string& model) {
  FigureQuery q;
  q.figure = name;
  q.gear_model = model;
  return q;
}

TEST(SqliteFigureColumns, EveryTrendedFigureHasItsColumn) {
  const auto file = testing::fresh_dir("SqliteFigureColumns") / "index.sqlite";
  { SqliteResultsStore store(file); }
  const auto columns = columns_of(file);
  ASSERT_FALSE(fleet_figures().empty());
  for (const auto& f : fleet_figures()) EXPECT_TRUE(columns.contains(f.column)) << f.column;
}

TEST(SqliteFigureColumns, ANewlyDeclaredFigureColumnIsAddedToAnOldStore) {
  const auto dir = testing::fresh_dir("SqliteNewColumn");
  const auto file = dir / "fleet.sqlite";
  storage::RunStore local(dir / "runs", "test");
  testing::SyntheticRun synthetic;
  synthetic.lost_motion_arcmin = 0.41;
  const auto old_id = testing::add_synthetic_run(local, synthetic);
  {
    SqliteResultsStore store(file);
    ASSERT_TRUE(store.publish(summarise_run(
        *local.find_run(old_id), testing::synthetic_results(old_id, synthetic), {"bench-a", ""})));
  }
  // The store as a build before static_lost_motion's trend was declared left it.
  exec(file, "ALTER TABLE fleet_runs DROP COLUMN static_lost_motion_arcmin");
  ASSERT_FALSE(columns_of(file).contains("static_lost_motion_arcmin"));
  {
    SqliteResultsStore reader(file, SqliteResultsStore::Access::kReadOnly);
    const auto rows = reader.runs(FleetRunQuery{});
    ASSERT_EQ(rows.size(), 1u);
    EXPECT_FALSE(rows[0].figures.contains("static_lost_motion"));
    EXPECT_TRUE(rows[0].figures.contains("static_te_p2p"));
    EXPECT_TRUE(reader.trend(figure("static_lost_motion", synthetic.model)).empty());
  }
  EXPECT_FALSE(columns_of(file).contains("static_lost_motion_arcmin"));  // read-only: untouched
  SqliteResultsStore store(file);
  EXPECT_TRUE(columns_of(file).contains("static_lost_motion_arcmin"));
  EXPECT_EQ(store.schema_version(), sqlite_fleet_schema_version());
  ASSERT_EQ(store.runs(FleetRunQuery{}).size(), 1u);
  synthetic.lost_motion_arcmin = 0.43;
  const auto new_id = testing::add_synthetic_run(local, synthetic);
  ASSERT_TRUE(store.publish(summarise_run(
      *local.find_run(new_id), testing::synthetic_results(new_id, synthetic), {"bench-a", ""})));
  const auto points = store.trend(figure("static_lost_motion", synthetic.model));
  ASSERT_EQ(points.size(), 1u);
  EXPECT_EQ(points[0].run_id, new_id);
  EXPECT_DOUBLE_EQ(points[0].value, 0.43);
}

}  // namespace
}  // namespace wavebench::fleet
