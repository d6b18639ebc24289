// The run's end is recorded last (issue #22, item 1): a report that cannot be written (its name
// taken by a folder, as a file system refusing new files would) ends the run aborted with the
// report's path and the error in the reason; the index never says complete or PASS meanwhile,
// and results.json and status.json say aborted with it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(HostileResultsReport, AReportThatCannotBeWrittenEndsTheRunAbortedNotPass) {
  const fs::path root =
      fs::temp_directory_path() / ("wavebench-hostile-report-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto config = bench::default_simulated_bench_config();
  auto bench = bench::make_simulated_bench(config);
  bench->connect();
  storage::RunStore store(root, "test");

  RunRequest request;
  request.procedure = "static";
  request.options = {{"positions", 4},
                     {"loads_nm", {0}},
                     {"window_s", 0.1},
                     {"limits", {{"static_p2p_arcmin", 100}}}};
  request.config_text = config.text;
  request.twin = false;
  request.report = true;
  std::string id;
  // What the index said at each post-run phase: never complete before the end is recorded.
  std::vector<std::string> index_seen;
  const auto outcome = execute_run(*bench, store, request, [&](const RunProgress& p) {
    if (id.empty() && !p.run_id.empty()) {
      id = p.run_id;
      fs::create_directory(store.paths(id).dir / "report.html");
    }
    if (!id.empty()) {
      if (const auto r = store.find_run(id)) {
        index_seen.push_back(p.phase + ": " + storage::run_status_name(r->status));
      }
    }
  });
  bench->disconnect();

  std::printf("outcome: %s (%s)\n", storage::run_status_name(outcome.status),
              outcome.reason.c_str());
  EXPECT_EQ(outcome.status, storage::RunStatus::kAborted);
  const auto report = store.paths(id).dir / "report.html";
  EXPECT_EQ(outcome.reason.rfind("report not written: ", 0), 0u) << outcome.reason;
  EXPECT_NE(outcome.reason.find(report.string()), std::string::npos) << outcome.reason;
  EXPECT_NE(outcome.reason.find("Is a directory"), std::string::npos) << outcome.reason;
  for (const auto& seen : index_seen) {
    EXPECT_EQ(seen.find("complete"), std::string::npos) << "the index said " << seen;
  }
  const auto record = store.find_run(id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, storage::RunStatus::kAborted);
  EXPECT_EQ(record->reason, outcome.reason);
  EXPECT_FALSE(record->pass.has_value());
  EXPECT_TRUE(record->verdict.empty()) << record->verdict;
  const auto results = read_json(store.paths(id).results);
  EXPECT_EQ(results["status"], "aborted");
  EXPECT_EQ(results["reason"], outcome.reason);
  EXPECT_TRUE(results["verdict"].is_null());
  EXPECT_FALSE(results.contains("limit_checks"));
  EXPECT_TRUE(results["static"].is_array());  // the figures stay
  const auto status = read_json(store.paths(id).status);
  EXPECT_EQ(status["status"], "aborted");
  EXPECT_EQ(status["reason"], outcome.reason);
  fs::remove_all(root);
}

}  // namespace
}  // namespace wavebench::procedures
