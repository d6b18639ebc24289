#pragma once
// The parsers of the sections of a twin case, one per file, each filling its part of TwinCase.

#include <vector>

#include "wavebench/config/twin_case.hpp"
#include "yaml_section.hpp"

namespace wavebench::config {

void parse_gear_section(YamlSection& s, model::GearParams& gear);
void parse_te_section(YamlSection& s, model::GearParams& gear);
void parse_stiffness_section(YamlSection& s, model::StiffnessParams& stiffness);
void parse_backlash_section(YamlSection& s, model::BacklashParams& backlash);
void parse_damping_section(YamlSection& s, model::MeshDamping& damping);
void parse_friction_section(YamlSection& s, model::FrictionLaw& friction,
                            model::FrictionSide& side);
// Also sets gear.nominal_input_speed.
void parse_input_section(YamlSection& s, model::GearParams& gear);
void parse_load_section(YamlSection& s, model::LoadParams& load);
void parse_solver_section(YamlSection& s, model::SimulationOptions& solver);
void parse_analysis_section(YamlSection& s, analysis::AnalysisOptions& analysis);
// `defects:`, a list of {kind: tooth | rising_once_per_rev, ...}; needs the gear section read.
void parse_defects_section(std::vector<YamlSection> items, model::GearParams& gear);

}  // namespace wavebench::config
