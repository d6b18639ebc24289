// The `wavebench` binary's daemon commands (status, start --wait, runs, export, abort) against
// an in-process daemon with the fake bench: the command line is wired to the client.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>

#include "daemon_fixture.hpp"

namespace wavebench::daemon::testing {
namespace {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CommandResult run_wavebench(const std::string& args) {
  const std::string command = std::string(WAVEBENCH_CLI_PATH) + " " + args + " 2>&1";
  CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class CliBinaryTest : public DaemonFixture {
 protected:
  void SetUp() override {
    DaemonFixture::SetUp();
    std::ofstream(dir_ / "token") << kToken << "\n";
    args_ = " --daemon " + url() + " --token-file " + (dir_ / "token").string();
  }
  std::string args_;
};

TEST_F(CliBinaryTest, StatusStartRunsExportAbort) {
  auto r = run_wavebench("status" + args_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("state        ready"), std::string::npos) << r.output;

  r = run_wavebench("start static --option seconds=0.05 --wait" + args_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(" complete"), std::string::npos) << r.output;
  const auto runs = client().get("/api/runs").body["runs"];
  ASSERT_EQ(runs.size(), 1u);
  const auto id = runs[0]["id"].get<std::string>();

  r = run_wavebench("runs --status complete --procedure static" + args_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(id), std::string::npos) << r.output;

  const auto out = dir_ / "export";
  r = run_wavebench("export " + id + " --out " + out.string() + " --format csv" + args_);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("exported 50 samples"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out / "samples.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "results.json"));

  r = run_wavebench("abort" + args_);
  EXPECT_EQ(r.exit_code, 1) << r.output;  // no run active
  EXPECT_NE(r.output.find("no run is active"), std::string::npos) << r.output;
}

TEST_F(CliBinaryTest, ErrorsAreClearWithTheirExitStatus) {
  auto r = run_wavebench("status --daemon http://127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("no daemon answering"), std::string::npos) << r.output;
  r = run_wavebench("start spin" + args_);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  r = run_wavebench("start static --option seconds=-2" + args_);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("seconds"), std::string::npos) << r.output;
  r = run_wavebench("export R --format xml" + args_);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_TRUE(client().get("/api/runs").body["runs"].empty());
}

}  // namespace
}  // namespace wavebench::daemon::testing
