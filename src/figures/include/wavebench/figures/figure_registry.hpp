#pragma once
// Every declared figure, gathered from the procedures' *_figures.cpp in the registry's order:
// the one list the verdict, the results store, the report and the console read.

#include <nlohmann/json.hpp>
#include <span>
#include <string_view>
#include <vector>

#include "wavebench/figures/figure_declaration.hpp"

namespace wavebench::figures {

// All of them, procedure by procedure.
std::span<const FigureDeclaration> declared_figures();
// The figures a run of `procedure` may report: its own and those of any procedure ("*").
std::vector<const FigureDeclaration*> figures_of(std::string_view procedure);
// Null when none has that name.
const FigureDeclaration* find_declared_figure(std::string_view name);

// {"name", "procedure", "path", "uncertainty_path", "label", "unit", "display_unit",
//  "display_scale", "display_digits", "limit": {"kind", "key"} | null,
//  "fleet": {"name", "column", "what"} | null, "plot"}: what the console draws from.
nlohmann::json to_json(const FigureDeclaration& f);
nlohmann::json figures_json(std::string_view procedure);
nlohmann::json all_figures_json();

}  // namespace wavebench::figures
