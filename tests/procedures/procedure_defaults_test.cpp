// configs/procedures/*.yaml document the procedures' defaults: they must be the defaults.
#include <gtest/gtest.h>

#include <filesystem>

#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/lost_motion_procedure.hpp"
#include "wavebench/procedures/procedure_options_file.hpp"
#include "wavebench/procedures/static_te_procedure.hpp"
#include "wavebench/procedures/torsional_procedure.hpp"

namespace wavebench::procedures {
namespace {

const std::filesystem::path kDir =
    std::filesystem::path(WAVEBENCH_SOURCE_DIR) / "configs" / "procedures";

TEST(ProcedureDefaults, TheShippedYamlFilesAreTheCompiledDefaults) {
  EXPECT_EQ(StaticTeOptions::from_json(load_procedure_options(kDir / "static.yaml")).to_json(),
            StaticTeOptions{}.to_json());
  EXPECT_EQ(DynamicTeOptions::from_json(load_procedure_options(kDir / "dynamic.yaml")).to_json(),
            DynamicTeOptions{}.to_json());
  EXPECT_EQ(
      LostMotionOptions::from_json(load_procedure_options(kDir / "lost-motion.yaml")).to_json(),
      LostMotionOptions{}.to_json());
  EXPECT_EQ(TorsionalOptions::from_json(load_procedure_options(kDir / "torsional.yaml")).to_json(),
            TorsionalOptions{}.to_json());
}

TEST(ProcedureDefaults, YamlScalarsBecomeNumbersBooleansAndStrings) {
  const auto j = procedure_options_from_yaml("a: 3\nb: 0.5\nc: [0, 60]\nd: true\ne: '12'\nf: x\n");
  EXPECT_EQ(j["a"], 3);
  EXPECT_EQ(j["b"], 0.5);
  EXPECT_EQ(j["c"], nlohmann::json({0, 60}));
  EXPECT_EQ(j["d"], true);
  EXPECT_EQ(j["e"], "12");
  EXPECT_EQ(j["f"], "x");
  EXPECT_THROW(procedure_options_from_yaml("- 1\n- 2\n", "list.yaml"), std::invalid_argument);
  EXPECT_THROW(procedure_options_from_yaml("a: [1,\n", "bad.yaml"), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::procedures
