#pragma once
// Every procedure a run request may name, in one table: its name, what the console shows of it
// and how its options become a procedure. Plans and runs go through the procedure itself
// (AnyProcedure), so a new procedure is one entry here and one alternative of the variant.

#include <nlohmann/json.hpp>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "wavebench/runs/dynamic_te_procedure.hpp"
#include "wavebench/runs/lost_motion_procedure.hpp"
#include "wavebench/runs/option_reader.hpp"
#include "wavebench/runs/static_te_procedure.hpp"
#include "wavebench/runs/torsional_procedure.hpp"

namespace wavebench::runs {

using AnyProcedure =
    std::variant<StaticTeProcedure, DynamicTeProcedure, LostMotionProcedure, TorsionalProcedure>;

struct ParsedProcedure {
  AnyProcedure procedure;
  nlohmann::json options;  // every option, defaults filled in (results.json "options")
};

struct ProcedureEntry {
  const char* name;
  const char* title;
  const char* description;
  std::vector<OptionSpec> (*options)();
  // Throws std::invalid_argument naming the key, the value and what was expected.
  ParsedProcedure (*parse)(const nlohmann::json& options);
};

std::span<const ProcedureEntry> procedure_entries();
// Null when no procedure has that name.
const ProcedureEntry* find_procedure(std::string_view name);
// "static, dynamic, lost-motion or torsional": for the refusal of an unknown name.
std::string procedure_name_list();

}  // namespace wavebench::runs
