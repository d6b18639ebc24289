// An aborted run keeps the figures it had finished (issue #22, item 5, second half): a static
// run on the simulated bench whose drive faults during its 60 N·m passes used to write a
// results.json without its finished 0 N·m passes (the samples were kept). Now they are in
// results.json, marked as from an aborted run (`partial`), and there is no verdict.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_executor.hpp"
#include "wavebench/simdevices/simulated_bench.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::procedures {
namespace {

namespace fs = std::filesystem;

TEST(HostileAbortedFigures, AStaticRunTrippedDuringItsSecondLoadKeepsItsFinishedPasses) {
  const fs::path root =
      fs::temp_directory_path() / ("wavebench-hostile-aborted-" + std::to_string(::getpid()));
  fs::remove_all(root);
  const auto config = bench::default_simulated_bench_config();
  auto bench = bench::make_simulated_bench(config);
  bench->connect();
  auto* access = bench::simulated_access(*bench);
  ASSERT_NE(access, nullptr);
  storage::RunStore store(root, "test");

  RunRequest request;
  request.procedure = "static";
  // With a limit the finished passes would meet: no verdict for them all the same.
  request.options = {{"positions", 4},
                     {"loads_nm", {0, 60}},
                     {"window_s", 0.1},
                     {"limits", {{"static_p2p_arcmin", 100}}}};
  request.config_text = config.text;
  request.twin = false;
  request.report = true;
  bool tripped = false;
  int at_60 = 0;
  std::string trip_phase;
  const auto outcome = execute_run(*bench, store, request, [&](const RunProgress& p) {
    // At the second position of the 60 N·m forward pass: both 0 N·m passes are finished.
    if (!tripped && p.phase.find("forward 60") != std::string::npos && ++at_60 == 2) {
      tripped = true;
      trip_phase = p.phase;
      access->devices().drive().inject_fault(0x2310);  // continuous over-current
    }
  });
  bench->disconnect();

  ASSERT_TRUE(tripped) << "the run never reached its 60 N·m passes";
  std::printf("tripped in '%s': %s (%s)\n", trip_phase.c_str(),
              storage::run_status_name(outcome.status), outcome.reason.c_str());
  EXPECT_EQ(outcome.status, storage::RunStatus::kAborted);
  std::ifstream in(store.paths(outcome.run_id).results);
  const auto results = nlohmann::json::parse(in, nullptr, false);
  ASSERT_TRUE(results.is_object());
  EXPECT_EQ(results["status"], "aborted");
  EXPECT_FALSE(results.value("reason", "").empty());
  EXPECT_TRUE(results["verdict"].is_null()) << results["verdict"];
  EXPECT_FALSE(results.contains("limit_checks"));
  EXPECT_FALSE(results["pass"] == true);
  // The finished passes: forward and reverse at 0 N·m, all their positions, with figures.
  ASSERT_TRUE(results.contains("static") && results["static"].is_array())
      << results.dump().substr(0, 3000);
  const auto& passes = results["static"];
  ASSERT_EQ(passes.size(), 2u) << passes.dump().substr(0, 400);
  for (const auto& pass : passes) {
    EXPECT_EQ(pass["load_nm"], 0);
    EXPECT_EQ(pass["points"].size(), 4u);
    EXPECT_TRUE(pass["p2p_arcmin"].is_number()) << pass.dump().substr(0, 300);
  }
  EXPECT_EQ(passes[0]["direction"], "forward");
  EXPECT_EQ(passes[1]["direction"], "reverse");
  EXPECT_EQ(results["lost_motion"].size(), 1u);  // the 0 N·m pair's
  // Marked as from an aborted run.
  ASSERT_TRUE(results.contains("partial"));
  EXPECT_EQ(results["partial"]["from_aborted_run"], true);
  EXPECT_EQ(results["partial"]["finished"], 2);
  EXPECT_EQ(results["partial"]["planned"], 4);
  EXPECT_EQ(results["partial"]["unit"], "passes");
  // The index agrees: aborted, no verdict.
  const auto record = store.find_run(outcome.run_id);
  ASSERT_TRUE(record);
  EXPECT_EQ(record->status, storage::RunStatus::kAborted);
  EXPECT_FALSE(record->pass.has_value());
  EXPECT_TRUE(record->verdict.empty());
  std::printf("kept %zu finished passes (p2p %s, %s arcmin) of a run aborted: %s\n", passes.size(),
              passes[0]["p2p_arcmin"].dump().c_str(), passes[1]["p2p_arcmin"].dump().c_str(),
              outcome.reason.c_str());
  fs::remove_all(root);
}

}  // namespace
}  // namespace wavebench::procedures
