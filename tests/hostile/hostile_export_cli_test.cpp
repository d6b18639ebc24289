// `wavebench export --runs` as the user runs it (issue #22 items 2, 4, 5): on a full disk
// (RLIMIT_FSIZE, inherited by the CLI) every format exits 1 with a message, never a signal, and
// leaves no folder; another run's export folder and a running run are refused with exit 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "file_size_limit.hpp"
#include "hostile_cli.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::hostile {
namespace {

// A run folder as a run store holds it: samples.wbs and status.json.
void make_run(const fs::path& runs, const std::string& id, const std::string& status,
              std::uint64_t samples) {
  fs::create_directories(runs / id);
  {
    storage::SampleLogWriter log(runs / id / "samples.wbs");
    for (std::uint64_t i = 0; i < samples; ++i) {
      storage::SyncSample s;
      s.sync_counter = static_cast<std::uint32_t>(i % 200 + 1);
      s.flags = storage::kAllChannelsValid;
      s.receive_time_ns = static_cast<std::int64_t>(i) * 1'000'000;
      s.torque_nm = 5.0;
      log.append(s);
    }
  }
  write_file(runs / id / "status.json",
             R"({"id": ")" + id + R"(", "status": ")" + status + "\"}\n");
  write_file(runs / id / "results.json", R"({"verdict": "PASS"})");
}

TEST(HostileExportCli, EveryFormatOnAFullDiskExitsOneWithoutASignalOrAFolder) {
  Sandbox box("export-cli-full");
  const auto runs = box.root() / "runs";
  const std::string id = "20260101T000000.000000Z";
  make_run(runs, id, "complete", 30000);
  int tried = 0;
  for (const std::string format : {"hdf5", "mat", "csv", "json"}) {
    for (const rlim_t cap : {rlim_t{700}, rlim_t{100000}, rlim_t{1000000}}) {
      const auto out = box.root() / ("out-" + format + "-" + std::to_string(cap));
      CliResult r;
      {
        wavebench::testing::FileSizeLimit disk(cap);
        r = run_wavebench("export " + id + " --runs " + quoted(runs) + " --format " + format +
                              " --out " + quoted(out),
                          box.log("full-" + format));
      }
      ++tried;
      SCOPED_TRACE(format + " cap " + std::to_string(cap) + ": " + r.output);
      EXPECT_EQ(r.exit_code, 1);
      EXPECT_NE(r.output.find("wavebench: export " + id), std::string::npos);
      EXPECT_FALSE(fs::exists(out));
    }
  }
  std::cout << "CLI exports on a full disk: " << tried << "\n";
}

TEST(HostileExportCli, AnotherRunsFolderAndARunningRunAreRefusedWithExitTwo) {
  Sandbox box("export-cli-refusals");
  const auto runs = box.root() / "runs";
  const std::string a = "20260101T000000.000000Z", b = "20260101T000001.000000Z",
                    live = "20260101T000002.000000Z";
  make_run(runs, a, "complete", 100);
  make_run(runs, b, "complete", 50);
  make_run(runs, live, "running", 70);
  const auto out = box.root() / "out";
  ASSERT_EQ(run_wavebench("export " + a + " --runs " + quoted(runs) + " --out " + quoted(out),
                          box.log("a"))
                .exit_code,
            0);
  const auto before = listing(out);
  const auto r = run_wavebench(
      "export " + b + " --runs " + quoted(runs) + " --format hdf5 --out " + quoted(out),
      box.log("b"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("holds the export of run '" + a + "'"), std::string::npos) << r.output;
  EXPECT_EQ(listing(out), before);

  const auto live_out = box.root() / "live";
  const auto refused = run_wavebench(
      "export " + live + " --runs " + quoted(runs) + " --out " + quoted(live_out), box.log("live"));
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--partial"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(live_out));
  const auto partial = run_wavebench("export " + live + " --runs " + quoted(runs) +
                                         " --partial --format json --out " + quoted(live_out),
                                     box.log("partial"));
  ASSERT_EQ(partial.exit_code, 0) << partial.output;
  EXPECT_NE(partial.output.find("partial"), std::string::npos) << partial.output;
  const auto j = nlohmann::json::parse(read_file(live_out / "samples.json"));
  EXPECT_EQ(j.value("partial", false), true);
  EXPECT_EQ(j["samples"].size(), 70u);
}

}  // namespace
}  // namespace wavebench::hostile
