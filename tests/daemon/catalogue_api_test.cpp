// GET /api/procedures, GET /api/specs, a start naming a spec, and the history query of
// GET /api/runs (filters, paging, total) against an in-process daemon (fake bench).
#include <gtest/gtest.h>

#include "daemon_fixture.hpp"

namespace wavebench::daemon::testing {
namespace {

using CatalogueApiTest = DaemonFixture;

TEST_F(CatalogueApiTest, ProceduresServeTheirOptionsSchemaWithoutAToken) {
  const auto reply = client("").get("/api/procedures");
  ASSERT_EQ(reply.status, 200) << reply.body.dump();
  const auto& list = reply.body["procedures"];
  ASSERT_EQ(list.size(), 5u);
  EXPECT_EQ(list[0]["name"], "static");
  EXPECT_EQ(list[1]["name"], "dynamic");
  EXPECT_EQ(list[2]["name"], "lost-motion");
  EXPECT_EQ(list[3]["name"], "torsional");
  EXPECT_EQ(list[4]["name"], "endurance");
  const auto& rpm = list[1]["options"][0];
  EXPECT_EQ(rpm["name"], "input_rpm");
  EXPECT_EQ(rpm["type"], "number");
  EXPECT_EQ(rpm["unit"], "rpm");
  EXPECT_EQ(rpm["default"], 100);
  EXPECT_EQ(rpm["minimum"], 0);
  EXPECT_EQ(rpm["exclusive_minimum"], true);
  // Each procedure's declared figures (src/figures, issue #23): what the run page draws.
  bool hysteresis = false;
  for (const auto& f : list[3]["figures"]) {
    hysteresis |= f["name"] == "hysteresis_loss" &&
                  f["path"] == "torsional.hysteresis_loss_arcmin" &&
                  f["limit"]["key"] == "hysteresis_loss_arcmin" && f["display_unit"] == "arcmin";
  }
  EXPECT_TRUE(hysteresis) << list[3]["figures"].dump();
  EXPECT_EQ(client().post("/api/procedures").status, 405);
}

TEST_F(CatalogueApiTest, SpecsListTheShippedLimitsWithUnits) {
  const auto reply = client("").get("/api/specs");
  ASSERT_EQ(reply.status, 200) << reply.body.dump();
  bool found = false;
  for (const auto& spec : reply.body["specs"]) {
    if (spec["name"] != "csf-25-100") continue;
    found = true;
    EXPECT_EQ(spec["model"], "CSF-25-100-2A-GR");
    EXPECT_EQ(spec["lost_motion_at_percent"], 3);
    EXPECT_EQ(spec["limits"][0]["key"], "static_te_p2p");
    EXPECT_EQ(spec["limits"][0]["limit"], "static_p2p_arcmin");
    EXPECT_EQ(spec["limits"][0]["value"], 1);
    EXPECT_EQ(spec["limits"][0]["unit"], "arcmin");
  }
  EXPECT_TRUE(found) << reply.body.dump();
  EXPECT_TRUE(reply.body["refused"].empty()) << reply.body.dump();
}

TEST_F(CatalogueApiTest, ABadUnitSerialOrOperatorIsRefusedNamingTheFieldAndNothingStarts) {
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {{{"procedure", "static"}, {"unit_serial", 42}}, "unit_serial: got 42, expected a string"},
      {{{"procedure", "static"}, {"unit_serial", "SN 1"}}, "unit_serial: got 'SN 1', expected"},
      {{{"procedure", "static"}, {"operator", "a\u0001b"}}, "operator: got 'a\\x01b', expected"},
      {{{"procedure", "static"}, {"operator", std::string(65, 'o')}}, "operator: got '"},
  };
  for (const auto& [body, prefix] : cases) {
    const auto reply = client().post("/api/runs", body);
    EXPECT_EQ(reply.status, 400) << body.dump();
    const auto detail = reply.body.value("detail", std::string());
    EXPECT_EQ(detail.rfind(prefix, 0), 0u) << detail;
  }
  EXPECT_EQ(client().get("/api/runs").body["total"], 0);
}

TEST_F(CatalogueApiTest, AnUnknownSpecIsRefusedNamingItAndTheKnownOnesAndNothingStarts) {
  const auto reply = client().post("/api/runs", {{"procedure", "static"}, {"spec", "csf-99"}});
  EXPECT_EQ(reply.status, 400);
  const auto detail = reply.body["detail"].get<std::string>();
  EXPECT_EQ(detail.rfind("spec: got 'csf-99', expected one of the known specs: ", 0), 0u) << detail;
  EXPECT_NE(detail.find("csf-25-100"), std::string::npos) << detail;
  EXPECT_EQ(client().post("/api/runs", {{"procedure", "static"}, {"spec", 3}}).status, 400);
  EXPECT_EQ(client().get("/api/runs").body["total"], 0);
  const auto started = client().post(
      "/api/runs",
      {{"procedure", "static"}, {"spec", "sim-seed004"}, {"options", {{"seconds", 0.05}}}});
  EXPECT_EQ(started.status, 201) << started.body.dump();
  ASSERT_TRUE(eventually([&] { return run_finished(); }));
}

TEST_F(CatalogueApiTest, HistoryPagesNewestFirstWithTheTotalAndFilters) {
  std::vector<std::string> ids;
  for (const char* procedure : {"static", "dynamic", "static", "static"}) {
    const auto started =
        client().post("/api/runs", {{"procedure", procedure}, {"options", {{"seconds", 0.05}}}});
    ASSERT_EQ(started.status, 201) << started.body.dump();
    ids.push_back(started.body["run_id"]);
    ASSERT_TRUE(eventually([&] { return run_finished(); }));
  }
  const auto page = client().get("/api/runs?limit=2&offset=1");
  ASSERT_EQ(page.status, 200) << page.body.dump();
  EXPECT_EQ(page.body["total"], 4);
  EXPECT_EQ(page.body["offset"], 1);
  EXPECT_EQ(page.body["limit"], 2);
  ASSERT_EQ(page.body["runs"].size(), 2u);
  EXPECT_EQ(page.body["runs"][0]["id"], ids[2]);
  EXPECT_EQ(page.body["runs"][1]["id"], ids[1]);
  EXPECT_EQ(page.body["runs"][0]["verdict"], "PASS");  // the fake launcher passes every run
  EXPECT_TRUE(page.body["runs"][0]["spec"].is_null());
  EXPECT_EQ(client().get("/api/runs").body["limit"], 50);

  const auto statics = client().get("/api/runs?procedure=static&verdict=pass&status=complete");
  EXPECT_EQ(statics.body["total"], 3);
  EXPECT_EQ(client().get("/api/runs?verdict=none").body["total"], 0);
  EXPECT_EQ(client().get("/api/runs?unit=SN-FAKE-1&procedure=dynamic").body["total"], 1);
  EXPECT_EQ(client().get("/api/runs?from=" + ids[1] + "&to=" + ids[2]).body["total"], 2);
  const std::string day =
      ids[0].substr(0, 4) + "-" + ids[0].substr(4, 2) + "-" + ids[0].substr(6, 2);
  EXPECT_EQ(client().get("/api/runs?from=" + day + "&to=" + day).body["total"], 4);
  EXPECT_EQ(client().get("/api/runs?to=2000-01-01").body["total"], 0);
}

TEST_F(CatalogueApiTest, BadHistoryParametersAreRefusedNamingKeyValueAndExpectation) {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"limit=0", "limit: got '0', expected an integer from 1 to 1000"},
      {"limit=1001", "limit: got '1001', expected an integer from 1 to 1000"},
      {"offset=-1", "offset: got '-1', expected an integer from 0"},
      {"verdict=maybe", "verdict: got 'maybe', expected pass, fail, undecided or none"},
      {"procedure=statik",
       "procedure: got 'statik', expected one of static, dynamic, lost-motion, torsional, "
       "endurance"},
      {"from=2026-13-01", "from: got '2026-13-01', expected an ISO date"},
      {"to=yesterday", "to: got 'yesterday', expected an ISO date"},
      {"from=2026-02-02&to=2026-02-01", "to: got '2026-02-01', expected a time not before from"},
      {"spec=../x", "spec: got '../x', expected a spec name"},
      {"colour=red", "colour: got 'red', expected a known filter"},
  };
  for (const auto& [query, message] : bad) {
    const auto reply = client().get("/api/runs?" + query);
    EXPECT_EQ(reply.status, 400) << query;
    EXPECT_EQ(reply.body.value("detail", "").rfind(message, 0), 0u)
        << query << ": " << reply.body.dump();
  }
}

}  // namespace
}  // namespace wavebench::daemon::testing
