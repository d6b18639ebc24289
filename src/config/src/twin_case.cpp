#include "wavebench/config/twin_case.hpp"

#include "twin_sections.hpp"
#include "wavebench/config/config_error.hpp"
#include "wavebench/config/config_text.hpp"

namespace wavebench::config {
namespace {

TwinCase parse_document(const YAML::Node& root) {
  YamlSection doc = document_section(root);
  TwinCase twin;
  twin.gear.name = doc.optional_label("name").value_or("");
  doc.text_or("description", "");  // free text for people

  YamlSection gear = doc.section("gear");
  parse_gear_section(gear, twin.gear);
  if (auto s = doc.optional_section("te")) parse_te_section(*s, twin.gear);
  YamlSection stiffness = doc.section("stiffness");
  parse_stiffness_section(stiffness, twin.gear.stiffness);
  if (auto s = doc.optional_section("backlash")) parse_backlash_section(*s, twin.gear.backlash);
  if (auto s = doc.optional_section("damping")) parse_damping_section(*s, twin.gear.damping);
  if (auto s = doc.optional_section("friction"))
    parse_friction_section(*s, twin.gear.friction, twin.gear.friction_side);
  YamlSection input = doc.section("input");
  parse_input_section(input, twin.gear);
  if (auto s = doc.optional_section("load")) parse_load_section(*s, twin.gear.load);
  if (auto s = doc.optional_section("solver")) parse_solver_section(*s, twin.solver);
  if (auto s = doc.optional_section("analysis")) parse_analysis_section(*s, twin.analysis);
  parse_defects_section(doc.section_list("defects"), twin.gear);
  doc.finish();
  return twin;
}

}  // namespace

TwinCase parse_twin_case(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = parse_config_yaml(yaml_text, source);
  try {
    TwinCase twin = parse_document(root);
    check_twin_run_budget(twin);
    return twin;
  } catch (const ConfigError& e) {
    throw e.with_source(source);
  } catch (const YAML::Exception& e) {
    throw ConfigError("", e.msg, "well-formed twin case", source);
  }
}

TwinCase load_twin_case(const std::filesystem::path& path) {
  return parse_twin_case(read_config_text(path), path.string());
}

}  // namespace wavebench::config
