// GET /api/fleet/* parameters as an attacker or a typo sends them (fleet_api.hpp): every bad
// one is answered 400 naming the key, the value and what was expected, before any store query;
// the bench's own store answers an empty trend honestly.
#include <gtest/gtest.h>

#include <string>

#include "test_dir.hpp"
#include "wavebench/daemon/fleet_api.hpp"
#include "wavebench/fleet/sqlite_results_store.hpp"

namespace wavebench::daemon::testing {
namespace {

class FleetQueriesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_test_dir();
    // The tables as the daemon's outbox makes them at its start.
    fleet::SqliteResultsStore(dir_ / "index.sqlite");
    queries_ = make_fleet_queries(fleet::ResultsConfig{}, dir_ / "index.sqlite");
  }
  ApiResponse get(const std::string& target) { return queries_(parse_http_target(target)); }

  std::filesystem::path dir_;
  FleetQueries queries_;
};

TEST_F(FleetQueriesTest, NonFiniteNumbersAreRefusedNamingTheKey) {
  const std::string spc = "/api/fleet/spc?figure=static_te_p2p&model=CSG-20&";
  for (const auto& [query, key] :
       std::initializer_list<std::pair<const char*, const char*>>{{"usl=nan", "usl"},
                                                                  {"lsl=-inf", "lsl"},
                                                                  {"load=inf", "load"},
                                                                  {"last=nan", "last"},
                                                                  {"usl=1e400", "usl"}}) {
    const auto r = get(spc + query);
    EXPECT_EQ(r.status, 400) << query;
    const auto detail = r.body.value("detail", std::string());
    EXPECT_EQ(detail.rfind(std::string(key) + ": got '", 0), 0U) << query << ": " << detail;
    EXPECT_NE(detail.find("finite number"), std::string::npos) << detail;
  }
}

TEST_F(FleetQueriesTest, LimitsOutOfOrderAndCountsOutOfRangeAreRefused) {
  auto r = get("/api/fleet/spc?figure=static_te_p2p&model=CSG-20&lsl=5&usl=1");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.value("detail", std::string()).find("lsl: got '5', expected below usl (1)"),
            std::string::npos)
      << r.body.dump();
  r = get("/api/fleet/runs?limit=1e9");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.value("detail", std::string()).find("limit: got '1e9'"), std::string::npos);
  r = get("/api/fleet/trend?figure=static_te_p2p&model=CSG-20&last=2.5");
  EXPECT_EQ(r.status, 400);
  r = get("/api/fleet/trend?figure=static_te_p2p&model=CSG-20&from=2026-02-31");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.body.value("detail", std::string()).find("from: got '2026-02-31'"), std::string::npos)
      << r.body.dump();
  r = get("/api/fleet/trend?figure=no_such_figure&model=CSG-20");
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(get("/api/fleet/nothing").status, 404);
}

TEST_F(FleetQueriesTest, AnEmptyStoreAnswersNoPoints) {
  // A trend takes no spec limits (the spc does): usl is refused, not silently ignored.
  EXPECT_EQ(get("/api/fleet/trend?figure=static_te_p2p&model=CSG-20&usl=7").status, 400);
  const auto r = get("/api/fleet/trend?figure=static_te_p2p&model=CSG-20");
  ASSERT_EQ(r.status, 200) << r.body.dump();
  EXPECT_TRUE(r.body["points"].empty());
  const auto s = get("/api/fleet/spc?figure=static_te_p2p&model=CSG-20&lsl=0&usl=7");
  ASSERT_EQ(s.status, 200) << s.body.dump();
  EXPECT_TRUE(s.body["points"].empty());
}

}  // namespace
}  // namespace wavebench::daemon::testing
