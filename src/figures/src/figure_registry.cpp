#include "wavebench/figures/figure_registry.hpp"

#include <array>

namespace wavebench::figures {

// One procedure's declarations, each in its own <procedure>_figures.cpp: a new procedure's
// figures are that file and one line here and in kSources.
std::span<const FigureDeclaration> static_te_figures();
std::span<const FigureDeclaration> dynamic_te_figures();
std::span<const FigureDeclaration> lost_motion_figures();
std::span<const FigureDeclaration> torsional_figures();
std::span<const FigureDeclaration> endurance_figures();
std::span<const FigureDeclaration> twin_figures();

namespace {

// The procedures' declarations; the twin's last (any procedure may calibrate the twin beside
// the bench). This order is the verdict's and the fleet page's.
constexpr std::array kSources = {&static_te_figures, &lost_motion_figures, &dynamic_te_figures,
                                 &torsional_figures, &endurance_figures,   &twin_figures};

std::vector<FigureDeclaration> gathered() {
  std::vector<FigureDeclaration> all;
  for (const auto source : kSources) {
    const auto some = source();
    all.insert(all.end(), some.begin(), some.end());
  }
  return all;
}

}  // namespace

std::span<const FigureDeclaration> declared_figures() {
  static const std::vector<FigureDeclaration> all = gathered();
  return all;
}

std::vector<const FigureDeclaration*> figures_of(std::string_view procedure) {
  std::vector<const FigureDeclaration*> out;
  for (const auto& f : declared_figures()) {
    if (procedure == f.procedure || std::string_view(f.procedure) == "*") out.push_back(&f);
  }
  return out;
}

const FigureDeclaration* find_declared_figure(std::string_view name) {
  for (const auto& f : declared_figures()) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

}  // namespace wavebench::figures
