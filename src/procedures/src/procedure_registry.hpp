#pragma once
// Every procedure a run request may name, in one table: its name, what the console shows of it
// and how its options become a procedure. Plans and runs go through the procedure itself
// (AnyProcedure), so a new procedure is one entry here, one alternative of the variant and
// its kResultsSection (where its outcome goes in results.json).

#include <nlohmann/json.hpp>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "wavebench/procedures/dynamic_te_procedure.hpp"
#include "wavebench/procedures/endurance_procedure.hpp"
#include "wavebench/procedures/lost_motion_procedure.hpp"
#include "wavebench/procedures/option_reader.hpp"
#include "wavebench/procedures/static_te_procedure.hpp"
#include "wavebench/procedures/torsional_procedure.hpp"

namespace wavebench::procedures {

using AnyProcedure = std::variant<StaticTeProcedure, DynamicTeProcedure, LostMotionProcedure,
                                  TorsionalProcedure, EnduranceProcedure>;

struct ParsedProcedure {
  AnyProcedure procedure;
  nlohmann::json options;  // every option, defaults filled in (results.json "options")
  int repeats = 1;         // the procedure run this many times in one run (options "repeats")
};

// `repeats` belongs to every procedure (issue #11): the registry takes it off the options
// before the procedure parses them, and adds it to each procedure's schema, so that a new
// procedure gets it without a line of its own.
inline constexpr const char* kRepeatsKey = "repeats";
inline constexpr int kMaxRepeats = 100;
OptionSpec repeats_option_spec();

struct ProcedureEntry {
  const char* name;
  const char* title;
  const char* description;
  std::vector<OptionSpec> (*options)();  // the procedure's own, without `repeats`
  // Throws std::invalid_argument naming the key, the value and what was expected.
  ParsedProcedure (*parse)(const nlohmann::json& options);
};

std::span<const ProcedureEntry> procedure_entries();
// Null when no procedure has that name.
const ProcedureEntry* find_procedure(std::string_view name);
// The options a request may give `entry`: its own and `repeats`.
std::vector<OptionSpec> procedure_options(const ProcedureEntry& entry);
// entry.parse() with `repeats` taken off first (integer 1..kMaxRepeats, default 1). Throws
// std::invalid_argument naming the key, the value and what was expected.
ParsedProcedure parse_procedure(const ProcedureEntry& entry, const nlohmann::json& options);
// "static, dynamic, lost-motion, torsional or endurance": for the refusal of an unknown name.
std::string procedure_name_list();

}  // namespace wavebench::procedures
