// The API's route table (DaemonApi::routes()) walked row by row: every route that needs a login
// refuses a request without one, and every known path answers a method it lacks with 405 and
// an Allow header that lists the table's methods for that path.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "daemon_fixture.hpp"
#include "wavebench/daemon/api_route.hpp"
#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon::testing {
namespace {

class RouteTableTest : public DaemonFixture {
 protected:
  ApiResponse send(const std::string& method, const std::string& target) const {
    ApiRequest request;
    request.method = method;
    request.target = target;
    request.host = "127.0.0.1:" + std::to_string(daemon_->port());
    request.client = "127.0.0.1";
    return daemon_->api().handle(request);
  }
};

// A concrete path for a pattern: every parameter filled with a well-formed run id (it names
// no run), "{action}" with a manual action.
std::string path_for(std::string_view pattern) {
  std::string out;
  std::size_t i = 0;
  while (i < pattern.size()) {
    if (pattern[i] == '{') {
      const auto end = pattern.find('}', i);
      out += pattern.substr(i, end - i + 1) == "{action}" ? "stop" : "20261122T045843.123456Z";
      i = end + 1;
    } else {
      out += pattern[i++];
    }
  }
  return out;
}

std::string allow_header(const ApiResponse& response) {
  for (const auto& [name, value] : response.headers) {
    if (name == "Allow") return value;
  }
  return "<none>";
}

TEST(RouteTable, EveryRowIsUnderApiAndNoMethodAndPatternTwice) {
  std::set<std::pair<std::string_view, std::string_view>> seen;
  for (const auto& route : DaemonApi::routes()) {
    EXPECT_TRUE(route.pattern.starts_with("/api/")) << route.pattern;
    EXPECT_NE(route.handler, nullptr) << route.pattern;
    EXPECT_TRUE(seen.emplace(route.method, route.pattern).second)
        << route.method << " " << route.pattern << " twice";
  }
  EXPECT_EQ(seen.size(), DaemonApi::routes().size());
}

TEST_F(RouteTableTest, EveryRouteThatNeedsALoginRefusesARequestWithout) {
  int checked = 0;
  for (const auto& route : DaemonApi::routes()) {
    if (route.auth == RouteAuth::kNone) continue;
    const auto path = path_for(route.pattern);
    const auto answer = send(std::string(route.method), path);
    EXPECT_EQ(answer.status, 401) << route.method << " " << path << ": " << answer.body.dump();
    ++checked;
  }
  // abort, stop, reset, manual, start a run, export: the table's own count, not less.
  EXPECT_GE(checked, 6);
}

TEST_F(RouteTableTest, AMethodThePathLacksIs405WithAllowListingTheTablesMethods) {
  std::map<std::string, std::vector<std::string_view>> methods_by_path;
  for (const auto& route : DaemonApi::routes()) {
    auto& methods = methods_by_path[path_for(route.pattern)];
    methods.push_back(route.method);
  }
  for (const auto& [path, methods] : methods_by_path) {
    for (const std::string wrong : {"PUT", "PATCH", "GET", "POST", "DELETE"}) {
      if (std::find(methods.begin(), methods.end(), wrong) != methods.end()) continue;
      const auto answer = send(wrong, path);
      EXPECT_EQ(answer.status, 405) << wrong << " " << path;
      EXPECT_EQ(allow_header(answer), method_list_text(methods)) << wrong << " " << path;
      EXPECT_NE(answer.body.value("detail", "").find(method_list_text(methods)), std::string::npos)
          << answer.body.dump();
    }
  }
  EXPECT_EQ(allow_header(send("POST", "/api/runs/20261122T045843.123456Z/export")), "GET");
  EXPECT_EQ(allow_header(send("PUT", "/api/session")), "GET, POST or DELETE");
  EXPECT_EQ(allow_header(send("DELETE", "/api/runs")), "GET or POST");
  EXPECT_EQ(allow_header(send("POST", "/history")), "GET");  // the console's pages
}

TEST_F(RouteTableTest, UnknownPathsAre404WhateverTheMethod) {
  for (const std::string method : {"GET", "POST", "DELETE"}) {
    for (const std::string path : {"/api/nothing", "/api/runs/a/b/c", "/api", "/api/status/x"}) {
      EXPECT_EQ(send(method, path).status, 404) << method << " " << path;
    }
  }
}

TEST_F(RouteTableTest, ARunIdThatIsNotOneIs404BeforeTheLogin) {
  const auto answer = send("GET", "/api/runs/not-a-run/export");
  EXPECT_EQ(answer.status, 404) << answer.body.dump();
}

}  // namespace
}  // namespace wavebench::daemon::testing
