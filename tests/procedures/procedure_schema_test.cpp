// The options schema comes from the declarations that parse the options: every option the
// reader accepts is in it, with the default from_json({}) gives and the range it enforces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "procedure_registry.hpp"
#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/lost_motion_procedure.hpp"
#include "wavebench/procedures/procedure_catalogue.hpp"
#include "wavebench/procedures/run_request_check.hpp"
#include "wavebench/procedures/static_te_procedure.hpp"
#include "wavebench/procedures/torsional_procedure.hpp"

namespace wavebench::procedures {
namespace {

// A value just outside the option's range, of its type.
nlohmann::json outside(const nlohmann::json& option, bool above) {
  const double bound = option[above ? "maximum" : "minimum"].get<double>();
  if (option["type"] == "integer") return static_cast<long long>(above ? bound + 1 : bound - 1);
  const double margin = std::max(1e-3, std::abs(bound) * 1e-3);
  const double x = above                                     ? bound + margin
                   : option["exclusive_minimum"].get<bool>() ? bound
                                                             : bound - margin;
  if (option["type"] != "number_list") return x;
  nlohmann::json list = option["default"];
  if (list.empty()) list = nlohmann::json::array({1, 1, 1, 1});
  list[0] = x;
  return list;
}

// The options a procedure runs with, every default filled in (what results.json records),
// `repeats` among them (the registry's, for every procedure).
nlohmann::json parse(const std::string& procedure, const nlohmann::json& options) {
  return parse_procedure(*find_procedure(procedure), options).options;
}

class ProcedureSchema : public ::testing::TestWithParam<std::string> {};

TEST_P(ProcedureSchema, EveryAcceptedKeyIsDescribedWithItsDefault) {
  const auto& name = GetParam();
  const auto catalogue = procedures_json()["procedures"];
  nlohmann::json entry;
  for (const auto& p : catalogue) {
    if (p["name"] == name) entry = p;
  }
  ASSERT_TRUE(entry.is_object()) << name;
  EXPECT_FALSE(entry["title"].get<std::string>().empty());
  EXPECT_FALSE(entry["description"].get<std::string>().empty());

  // The defaults are what a request without options runs with.
  const auto defaults = parse(name, nlohmann::json::object());
  std::set<std::string> described;
  for (const auto& o : entry["options"]) {
    const auto key = o["name"].get<std::string>();
    described.insert(key);
    ASSERT_TRUE(defaults.contains(key)) << name << "." << key;
    EXPECT_EQ(o["default"], defaults[key]) << name << "." << key;
    const auto type = o["type"].get<std::string>();
    EXPECT_TRUE(type == "number" || type == "integer" || type == "boolean" || type == "number_list")
        << type;
    EXPECT_TRUE(o.contains("unit")) << key;
    EXPECT_FALSE(o["description"].get<std::string>().empty()) << key;
    if (type == "number_list") {
      EXPECT_GE(o["min_items"].get<int>(), 1) << key;
      EXPECT_LE(o["max_items"].get<int>(), 64) << key;
    }
    // The schema's default is itself accepted.
    EXPECT_NO_THROW(parse(name, {{key, o["default"]}})) << name << "." << key;
  }
  // ... and every key the parser fills in is described (the reader refuses the rest).
  for (const auto& [key, value] : defaults.items()) {
    EXPECT_TRUE(described.count(key)) << name << "." << key << " is not in the schema";
  }
}

TEST_P(ProcedureSchema, AValueOutsideTheDescribedRangeIsRefusedNamingTheKey) {
  const auto& name = GetParam();
  int checked = 0;
  const auto catalogue = procedures_json();
  for (const auto& p : catalogue["procedures"]) {
    if (p["name"] != name) continue;
    for (const auto& o : p["options"]) {
      const auto key = o["name"].get<std::string>();
      for (const bool above : {false, true}) {
        if (!o.contains(above ? "maximum" : "minimum")) continue;
        const auto value = outside(o, above);
        try {
          parse(name, {{key, value}});
          ADD_FAILURE() << name << "." << key << " = " << value.dump()
                        << " accepted outside the schema's range";
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find(name + "." + key), std::string::npos) << e.what();
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 4);
}

INSTANTIATE_TEST_SUITE_P(Procedures, ProcedureSchema,
                         ::testing::Values("static", "dynamic", "lost-motion", "torsional",
                                           "endurance"),
                         [](const auto& param_info) {
                           return param_info.param == "lost-motion" ? std::string("lost_motion")
                                                                    : param_info.param;
                         });

TEST(ProcedureRegistry, NamesTheProceduresAndRefusesAnUnknownOneAsBefore) {
  EXPECT_EQ(procedure_names(), (std::vector<std::string>{"static", "dynamic", "lost-motion",
                                                         "torsional", "endurance"}));
  RunRequest request;
  request.procedure = "statik";
  try {
    check_run_request(request, bench::BenchDescription{}, 0, RunBudget{});
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "procedure: got 'statik', expected static, dynamic, lost-motion, torsional or "
                 "endurance");
  }
}

TEST(ProcedureRegistry, UnknownOptionsAreStillRefusedWithTheKnownKeysInOrder) {
  try {
    DynamicTeOptions::from_json({{"rpm", 100}});
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "dynamic: unknown option 'rpm' (value '100'), expected one of: input_rpm, "
                 "run_in_s, output_revolutions, load_nm, max_peaks, harmonics");
  }
}

TEST(ProcedureRegistry, ASchemaEntryHasTheDeclaredUnitAndBounds) {
  const auto schema = StaticTeOptions::schema();
  ASSERT_FALSE(schema.empty());
  EXPECT_EQ(schema[0].name, "positions");
  const auto window = std::find_if(schema.begin(), schema.end(),
                                   [](const auto& o) { return o.name == "window_s"; });
  ASSERT_NE(window, schema.end());
  const auto j = window->to_json();
  EXPECT_EQ(j["type"], "number");
  EXPECT_EQ(j["unit"], "s");
  EXPECT_EQ(j["default"], 0.5);
  EXPECT_EQ(j["minimum"], 0);
  EXPECT_EQ(j["maximum"], 600);
  EXPECT_EQ(j["exclusive_minimum"], true);
  const auto torques = LostMotionOptions::schema()[1].to_json();
  EXPECT_EQ(torques["name"], "torques_nm");
  EXPECT_EQ(torques["type"], "number_list");
  EXPECT_EQ(torques["unit"], "N·m");
  EXPECT_EQ(torques["min_items"], 4);
  EXPECT_EQ(torques["max_items"], 64);
  EXPECT_EQ(torques["default"], nlohmann::json::array());
}

}  // namespace
}  // namespace wavebench::procedures
