// The strict YAML text checks (drivers/strict_yaml through config::parse_config_yaml) and the
// twin's run budgets, without the CLI.
#include "wavebench/config/config_text.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

namespace wavebench::config {
namespace {

ConfigError refusal(const std::string& text) {
  try {
    (void)parse_config_yaml(text, "t.yaml");
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.source(), "t.yaml");
    return e;
  }
  ADD_FAILURE() << "accepted: " << text;
  return ConfigError("", "", "");
}

TEST(ConfigText, DuplicateKeysAreRefusedAtAnyDepthWithBothLines) {
  auto e = refusal("a: 1\nb: 2\na: 3\n");
  EXPECT_EQ(e.key(), "a");
  EXPECT_EQ(e.value(), "3");
  EXPECT_NE(e.expected().find("line 1 and line 3"), std::string::npos) << e.expected();
  e = refusal("a:\n  b:\n    - {c: 1}\n    - {c: 1, d: 2, c: 3}\n");
  EXPECT_EQ(e.key(), "a.b[1].c");
}

TEST(ConfigText, EmptyBlankAndCommentOnlyDocumentsAreRefused) {
  for (const std::string text :
       {"", "\n\n", "   \t\n", "# just this\n", "~\n", "null\n", "---\n"}) {
    EXPECT_EQ(refusal(text).key(), "(document)") << text;
  }
}

TEST(ConfigText, NonUtf8NamesTheKeyPathLineAndColumn) {
  const auto e = refusal("top:\n  inner:\n    serial: \"SN\xC3\x28\"\n");
  EXPECT_EQ(e.key(), "top.inner.serial");
  EXPECT_NE(e.expected().find("byte 0xC3 at line 3, column 16"), std::string::npos) << e.expected();
  EXPECT_NE(e.value().find("\\xC3"), std::string::npos) << e.value();
  // Valid multi-byte UTF-8 (units such as "µm" or names with accents) passes.
  EXPECT_NO_THROW((void)parse_config_yaml("name: \"Zürich µ 😀\"\n", "t.yaml"));
}

TEST(ConfigText, SizeNestingAndAliasBombsAreBounded) {
  std::string big = "a: 1\n";
  big.resize((1u << 20) + 1, '#');
  EXPECT_NE(refusal(big).expected().find("at most 1048576 bytes"), std::string::npos);
  std::string deep = "a: ";
  for (int i = 0; i < 40; ++i) deep += "[";
  for (int i = 0; i < 40; ++i) deep += "]";
  EXPECT_NE(refusal(deep).expected().find("nested at most 32"), std::string::npos);
  std::string shallow = "a: ";
  for (int i = 0; i < 20; ++i) shallow += "[";
  for (int i = 0; i < 20; ++i) shallow += "]";
  EXPECT_NO_THROW((void)parse_config_yaml(shallow, "t.yaml"));
  std::string bomb = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 7; ++i) {
    const std::string p = "*l" + std::to_string(i - 1);
    bomb += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [" + p + ", " + p + ", " + p +
            ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + ", " + p + "]\n";
  }
  EXPECT_NE(refusal(bomb).expected().find("nodes"), std::string::npos);
}

TEST(ConfigText, AFolderIsNotAConfig) {
  try {
    (void)read_config_text(std::filesystem::temp_directory_path());
    ADD_FAILURE() << "a folder was read";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "(file)");
    EXPECT_NE(e.expected().find("not a folder"), std::string::npos);
  }
}

TEST(TwinRunBudget, EstimatesFromTEndStepAndSampleRate) {
  TwinCase twin;
  twin.solver.t_end = 300;
  twin.solver.sample_rate = 100e3;
  const auto e = estimate_twin_run(twin);
  EXPECT_NEAR(e.output_samples, 30e6, 10);
  EXPECT_GT(e.output_bytes, kMaxTwinOutputBytes);
  try {
    check_twin_run_budget(twin);
    ADD_FAILURE() << "300 s at 100 kHz accepted";
  } catch (const ConfigError& err) {
    EXPECT_EQ(err.key(), "solver.t_end");
    EXPECT_EQ(err.value(), "300 s");
    EXPECT_NE(err.expected().find("fits in 2 GiB (this one needs 7.2 GiB at 100 kHz output"),
              std::string::npos)
        << err.expected();
  }
  twin.solver.t_end = 100;
  twin.solver.sample_rate = 1000;
  twin.solver.method = model::SolverMethod::kRk4;
  twin.solver.fixed_step = 1e-7;
  EXPECT_NEAR(estimate_twin_run(twin).steps, 1e9, 1);
  try {
    check_twin_run_budget(twin, "--t-end");
    ADD_FAILURE() << "1e9 steps accepted";
  } catch (const ConfigError& err) {
    EXPECT_EQ(err.key(), "solver.fixed_step");
    EXPECT_NE(err.expected().find("--t-end"), std::string::npos) << err.expected();
  }
  twin.solver.fixed_step = 1e-5;  // 1e7 steps: within budget
  EXPECT_NO_THROW(check_twin_run_budget(twin));
}

}  // namespace
}  // namespace wavebench::config
