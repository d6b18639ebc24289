// The fleet stores' shared queries (fleet_sql.hpp): the same filters give the same parameters
// in both dialects, numbered in order as each server expects, and a bad bound is refused before
// any SQL is made. What the queries answer is the contract suite's (results_store_contract.hpp).
#include "fleet_sql.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace wavebench::fleet {
namespace {

TEST(FleetSql, ParametersAreNumberedInOrderInEachDialect) {
  FleetRunQuery q;
  q.gear_model = "CSG-20-160";
  q.status = "complete";
  q.from = "2026-11-24";
  const auto pg = runs_query(q, kPostgresSql);
  const auto lite = runs_query(q, kSqliteSql);
  EXPECT_NE(pg.sql.find("WHERE gear_model = $1 AND status = $2 AND started_at >= $3"),
            std::string::npos)
      << pg.sql;
  EXPECT_NE(lite.sql.find("WHERE gear_model = ?1 AND status = ?2 AND started_at >= ?3"),
            std::string::npos)
      << lite.sql;
  const SqlParams expected = {"CSG-20-160", "complete", "2026-11-24T00:00:00.000000Z"};
  EXPECT_EQ(pg.params, expected);
  EXPECT_EQ(lite.params, expected);
  // PostgreSQL reads its timestamptz back in the SQLite store's one text form.
  EXPECT_NE(pg.sql.find("to_char(started_at AT TIME ZONE 'UTC'"), std::string::npos);
  EXPECT_EQ(lite.sql.find("to_char"), std::string::npos);
  EXPECT_NE(lite.sql.find("LIMIT 50"), std::string::npos);
}

TEST(FleetSql, OnePassTrendJoinsThePassesAndCastsTheLoad) {
  FigureQuery q;
  q.figure = "static_te_p2p";
  q.gear_model = "CSG-20-160";
  q.direction = "forward";
  q.load_nm = 60;
  q.last = 5;
  const auto& figure = find_fleet_figure("static_te_p2p");
  const auto pg = trend_query(q, figure, kPostgresSql);
  const auto lite = trend_query(q, figure, kSqliteSql);
  EXPECT_NE(pg.sql.find("p.direction = $2 AND abs(p.load_nm - $3::double precision) < 1e-9"),
            std::string::npos)
      << pg.sql;
  EXPECT_NE(lite.sql.find("p.direction = ?2 AND abs(p.load_nm - CAST(?3 AS REAL)) < 1e-9"),
            std::string::npos)
      << lite.sql;
  const SqlParams expected = {"CSG-20-160", "forward", "60"};
  EXPECT_EQ(pg.params, expected);
  EXPECT_EQ(lite.params, expected);
  EXPECT_NE(pg.sql.find("LIMIT 5"), std::string::npos);
}

TEST(FleetSql, ABadBoundIsRefusedNamingItsKey) {
  FleetRunQuery q;
  q.to = "yesterday";
  try {
    runs_query(q, kSqliteSql);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("to"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("yesterday"), std::string::npos) << e.what();
  }
}

TEST(FleetSql, NumbersReadBackExactlyAndNonFiniteIsNull) {
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(std::stod(*number_text(1.0 / 3.0)), 1.0 / 3.0);
  EXPECT_FALSE(number_text(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(number_text(std::nullopt));
  EXPECT_FALSE(text_or_null(""));
}

}  // namespace
}  // namespace wavebench::fleet
