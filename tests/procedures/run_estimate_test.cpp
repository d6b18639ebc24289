// The run plan's disk estimate (issue #9): a bench that records extra channels writes wider
// sample log records, and the estimate must count them. Checked against the bytes the sample
// log writer really puts on disk for that bench's channels.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/bench/bench_factory.hpp"
#include "wavebench/procedures/run_plan.hpp"
#include "wavebench/storage/sample_log.hpp"

namespace wavebench::procedures {
namespace {

const std::filesystem::path kBenches =
    std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "benches";

// configs/benches/sim-input-encoder.yaml with a second CiA 406 encoder: two extra channels.
bench::BenchConfig two_extra_channel_config() {
  std::ifstream in(kBenches / "sim-input-encoder.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string anchor = "\ndevices:";
  const auto at = yaml.find('\n', yaml.find(anchor) + 1);
  yaml.insert(at + 1,
              "  theta_out_encoder:\n    kind: cia406_encoder\n    node: 6\n"
              "    counts_per_turn: 1048576\n    turns: 1\n");
  return bench::parse_bench_config(yaml, kBenches);
}

TEST(RunEstimate, SampleLogBytesAreWhatTheLogWritesForTheBenchsExtraChannels) {
  const auto config = two_extra_channel_config();
  const auto bench = bench::make_bench(config);
  const auto channels = bench->extra_channels();
  ASSERT_EQ(channels.size(), 2u);

  RunPlan plan;
  plan.bench_time_s = 1.234;  // 1234 SYNCs at 1 ms
  const RunEstimate e = estimate_run(plan, bench->description(), channels.size(), /*twin=*/false);
  ASSERT_EQ(e.samples, 1234u);

  const auto path = std::filesystem::temp_directory_path() /
                    ("wavebench-run-estimate-" + std::to_string(::getpid()) + ".wbs");
  {
    storage::SampleLogWriterOptions options;
    options.extra_channels = channels;
    storage::SampleLogWriter writer(path, options);
    storage::SyncSample s;
    for (std::uint64_t i = 0; i < e.samples; ++i) {
      s.sync_counter = static_cast<std::uint32_t>(i % 240 + 1);
      s.flags = storage::kAllChannelsValid;
      s.extra_valid = 0b11;
      writer.append(s);
    }
    writer.close();
  }
  const auto written = std::filesystem::file_size(path);
  std::filesystem::remove(path);
  EXPECT_EQ(e.sample_log_bytes, written);
  // Each record carries 8 bytes per extra channel: 16 bytes a sample more than a plain bench.
  const RunEstimate plain = estimate_run(plan, bench->description(), 0, false);
  EXPECT_EQ(e.sample_log_bytes - plain.sample_log_bytes, e.samples * 16 + 2 * 48);
}

}  // namespace
}  // namespace wavebench::procedures
