#include "procedure_registry.hpp"

#include <array>

#include "wavebench/figures/figure_registry.hpp"
#include "wavebench/procedures/procedure_catalogue.hpp"

namespace wavebench::procedures {

namespace {

template <class Options, class Procedure>
ParsedProcedure parse_as(const nlohmann::json& options) {
  const auto o = Options::from_json(options);
  return {Procedure(o), o.to_json(), 1};
}

const std::array<ProcedureEntry, 5> kProcedures{{
    {"static", "Static TE",
     "Transmission error at equally spaced output positions, settled, forward and reverse, at "
     "each brake load",
     &StaticTeOptions::schema, &parse_as<StaticTeOptions, StaticTeProcedure>},
    {"dynamic", "Dynamic TE",
     "Transmission error at constant input speed over whole output revolutions: trace, order "
     "spectrum with named and aliased peaks",
     &DynamicTeOptions::schema, &parse_as<DynamicTeOptions, DynamicTeProcedure>},
    {"lost-motion", "Lost motion and stiffness",
     "Torque–twist over a brake torque ladder in both directions: lost motion at ± a fraction "
     "of rated torque and the stiffnesses K1, K2, K3",
     &LostMotionOptions::schema, &parse_as<LostMotionOptions, LostMotionProcedure>},
    {"torsional", "Torsional stiffness (locked output)",
     "The catalogues' torque–twist loop with the brake holding the output: first loading to "
     "+T_max, unloading to −T_max, back to zero; hysteresis loss, lost motion, backlash, "
     "K1/K2/K3 and T1/T2, each with its uncertainty",
     &TorsionalOptions::schema, &parse_as<TorsionalOptions, TorsionalProcedure>},
    {"endurance", "Endurance",
     "Hours at constant input speed and brake load: TE mean, p2p and RMS, the mesh lines and the "
     "brake temperature of every output revolution, as a trend (wear, run-in)",
     &EnduranceOptions::schema, &parse_as<EnduranceOptions, EnduranceProcedure>},
}};

}  // namespace

namespace {

void declare_repeats(OptionReader& r, int& repeats) {
  r.integer(kRepeatsKey, repeats, 1, kMaxRepeats,
            {"",
             "the procedure run this many times; figures are the mean, the spread between "
             "repeats enters their uncertainty"});
}

}  // namespace

OptionSpec repeats_option_spec() {
  int repeats = 1;
  OptionReader r("run");
  declare_repeats(r, repeats);
  return r.described().front();
}

std::vector<OptionSpec> procedure_options(const ProcedureEntry& entry) {
  auto options = entry.options();
  options.push_back(repeats_option_spec());
  return options;
}

ParsedProcedure parse_procedure(const ProcedureEntry& entry, const nlohmann::json& options) {
  nlohmann::json own = options;
  int repeats = 1;
  if (own.is_object() && own.contains(kRepeatsKey)) {
    const nlohmann::json given = {{kRepeatsKey, own[kRepeatsKey]}};
    OptionReader r(given, entry.name, {repeats_option_spec()});
    declare_repeats(r, repeats);
    own.erase(kRepeatsKey);
  }
  auto parsed = entry.parse(own);
  parsed.repeats = repeats;
  parsed.options[kRepeatsKey] = repeats;
  return parsed;
}

std::span<const ProcedureEntry> procedure_entries() {
  return kProcedures;
}

const ProcedureEntry* find_procedure(std::string_view name) {
  for (const auto& p : kProcedures) {
    if (name == p.name) return &p;
  }
  return nullptr;
}

std::string procedure_name_list() {
  std::string out;
  for (std::size_t i = 0; i < kProcedures.size(); ++i) {
    if (i > 0) out += i + 1 == kProcedures.size() ? " or " : ", ";
    out += kProcedures[i].name;
  }
  return out;
}

nlohmann::json procedures_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : kProcedures) {
    nlohmann::json options = nlohmann::json::array();
    for (const auto& o : procedure_options(p)) options.push_back(o.to_json());
    list.push_back({{"name", p.name},
                    {"title", p.title},
                    {"description", p.description},
                    {"options", options},
                    {"figures", figures::figures_json(p.name)}});
  }
  return {{"procedures", list}};
}

std::vector<std::string> procedure_names() {
  std::vector<std::string> out;
  for (const auto& p : kProcedures) out.emplace_back(p.name);
  return out;
}

}  // namespace wavebench::procedures
