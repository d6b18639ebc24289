#include "wavebench/storage/run_store.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <set>
#include <sstream>

#include "test_dir.hpp"
#include "wavebench/storage/sha256.hpp"

namespace wavebench::storage {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Sha256, MatchesTheFipsVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(RunStore, CreateRunWritesFolderConfigStatusAndIndex) {
  const auto root = testing::fresh_test_dir();
  RunStore store(root, "0.1.0-test");
  const auto id = store.create_run("static_te", "SN-42", "gear: xb-80\n", R"({"te_p2p_arcmin":6})");
  const auto p = store.paths(id);
  EXPECT_EQ(slurp(p.config), "gear: xb-80\n");
  EXPECT_TRUE(std::filesystem::exists(p.status));
  const auto run = store.find_run(id);
  ASSERT_TRUE(run);
  EXPECT_EQ(run->status, RunStatus::kRunning);
  EXPECT_EQ(run->unit_serial, "SN-42");
  EXPECT_EQ(run->procedure, "static_te");
  EXPECT_EQ(run->software_version, "0.1.0-test");
  EXPECT_EQ(run->config_hash, sha256_hex("gear: xb-80\n"));
  EXPECT_EQ(run->limits_json, R"({"te_p2p_arcmin":6})");
  EXPECT_FALSE(run->pass.has_value());
  EXPECT_EQ(nlohmann::json::parse(slurp(p.status))["status"], "running");
}

TEST(RunStore, IdsAreUniqueAndSortByCreation) {
  const auto root = testing::fresh_test_dir();
  RunStore store(root, "v");
  std::vector<std::string> ids;
  for (int i = 0; i < 50; ++i) ids.push_back(store.create_run("dynamic_te", "SN", "x"));
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), ids.size());
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  EXPECT_EQ(ids.front().size(), std::string("20261122T045843.123456Z").size());
}

TEST(RunStore, FinishAndResultsAreIndexedAndQueryable) {
  const auto root = testing::fresh_test_dir();
  RunStore store(root, "v");
  const auto a = store.create_run("static_te", "SN-1", "a");
  const auto b = store.create_run("static_te", "SN-2", "b");
  const auto c = store.create_run("lost_motion", "SN-1", "c");
  store.write_results(a, nlohmann::json{{"static", nlohmann::json::array()}});
  store.finish_run(a, RunStatus::kComplete, "", true);
  store.finish_run(b, RunStatus::kAborted, "heartbeat of node 3 lost", false);
  EXPECT_EQ(nlohmann::json::parse(slurp(store.paths(a).results))["static"].size(), 0u);

  RunQuery by_unit;
  by_unit.unit_serial = "SN-1";
  const auto sn1 = store.list_runs(by_unit);
  ASSERT_EQ(sn1.size(), 2u);
  EXPECT_EQ(sn1[0].id, c);  // newest first
  RunQuery aborted;
  aborted.status = RunStatus::kAborted;
  const auto ab = store.list_runs(aborted);
  ASSERT_EQ(ab.size(), 1u);
  EXPECT_EQ(ab[0].reason, "heartbeat of node 3 lost");
  EXPECT_EQ(ab[0].pass, std::optional<bool>(false));
  EXPECT_FALSE(ab[0].finished_at.empty());
  EXPECT_EQ(store.find_run(a)->pass, std::optional<bool>(true));
  EXPECT_THROW(store.finish_run("nope", RunStatus::kComplete), std::invalid_argument);
  EXPECT_THROW(store.finish_run(c, RunStatus::kIncomplete), std::invalid_argument);
  EXPECT_THROW(store.create_run("x", "y", "z", "{not json"), std::invalid_argument);
}

TEST(RunStore, ReopeningMarksRunningRunsIncomplete) {
  const auto root = testing::fresh_test_dir();
  std::string running, done;
  {
    RunStore store(root, "v");
    running = store.create_run("static_te", "SN", "x");
    done = store.create_run("static_te", "SN", "x");
    store.finish_run(done, RunStatus::kComplete);
  }
  RunStore reopened(root, "v");
  EXPECT_EQ(reopened.find_run(running)->status, RunStatus::kIncomplete);
  EXPECT_EQ(reopened.find_run(done)->status, RunStatus::kComplete);
  EXPECT_EQ(nlohmann::json::parse(slurp(reopened.paths(running).status))["status"], "incomplete");
  EXPECT_TRUE(reopened.recover().empty());
}

// A second process on a root another one writes: refused naming the holder, and the holder's
// running run left running (the refusal comes before recover()). Free again once it is gone.
TEST(RunStore, AnotherProcessWritingTheRootIsRefusedAndItsRunLeftRunning) {
  const auto root = testing::fresh_test_dir();
  int ready[2], release[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(release), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    int rc = 1;
    try {
      RunStore store(root, "v");
      const auto id = store.create_run("static_te", "SN", "x");
      const char c = 'r';
      char go = 0;
      if (::write(ready[1], &c, 1) == 1 && ::read(release[0], &go, 1) == 1) {
        // The refused open did not mark this live run incomplete.
        rc = store.find_run(id)->status == RunStatus::kRunning ? 0 : 3;
      }
    } catch (...) {
    }
    ::_exit(rc);
  }
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  try {
    RunStore second(root, "v");
    ADD_FAILURE() << "a second process opened the store";
  } catch (const RunStoreInUse& e) {
    EXPECT_NE(std::string(e.what()).find("in use by process " + std::to_string(child)),
              std::string::npos)
        << e.what();
  }
  ASSERT_EQ(::write(release[1], &c, 1), 1);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "child status " << status;
  // The holder is gone: the root opens, and recovers the run it left running.
  RunStore after(root, "v");
  const auto runs = after.list_runs();
  ASSERT_EQ(runs.size(), 1U);
  EXPECT_EQ(runs[0].status, RunStatus::kIncomplete);
  for (int fd : {ready[0], ready[1], release[0], release[1]}) ::close(fd);
}

TEST(RunStatus, ParseNamesTheExpectedValues) {
  EXPECT_EQ(parse_run_status("aborted"), RunStatus::kAborted);
  try {
    parse_run_status("done");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'done'"), std::string::npos);
  }
}

}  // namespace
}  // namespace wavebench::storage
