// Spec names in POST /api/runs that are not a shipped spec: each one is a 400 naming `spec`,
// the value and the known specs, and nothing is created or started.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "daemon_fixture.hpp"

namespace wavebench::daemon::testing {
namespace {

using HostileSpecHttp = DaemonFixture;

TEST_F(HostileSpecHttp, BadSpecNamesInAStartAreRefusedAndNothingStarts) {
  const std::vector<nlohmann::json> names = {"../configs/benches/sim",
                                             "../../../etc/passwd",
                                             "/etc/passwd",
                                             std::string(65, 'a'),
                                             std::string(10000, 'b'),
                                             "",
                                             ".hidden",
                                             "csf-25-100/",
                                             "csf-25-100.yaml",
                                             "nope",
                                             "csf 25",
                                             nlohmann::json::array({"csf-25-100"}),
                                             nlohmann::json::object(),
                                             25,
                                             true};
  int refused = 0;
  for (const auto& name : names) {
    const auto reply = client().post("/api/runs", {{"procedure", "static"}, {"spec", name}});
    EXPECT_EQ(reply.status, 400) << name.dump().substr(0, 80);
    const auto detail = reply.body.value("detail", "");
    EXPECT_EQ(detail.rfind("spec: got ", 0), 0u) << detail.substr(0, 200);
    EXPECT_LT(detail.size(), 600u);
    if (name.is_string()) {
      EXPECT_NE(detail.find("csf-25-100"), std::string::npos) << detail.substr(0, 200);
    }
    refused += reply.status == 400;
  }
  std::printf("%zu hostile spec names over HTTP, %d refused\n", names.size(), refused);
  EXPECT_EQ(refused, static_cast<int>(names.size()));
  EXPECT_EQ(client().get("/api/runs").body["total"], 0);
  EXPECT_EQ(bench_->state(), bench::BenchLifecycle::kInactive);
}

}  // namespace
}  // namespace wavebench::daemon::testing
