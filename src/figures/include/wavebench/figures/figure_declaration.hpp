#pragma once
// One figure a procedure reports, declared once (issue #23 item 1, OpenHTF's measurement): the
// verdict table, the results store's typed columns and their migrations, the run summary, the
// report's figure table and the console's run page are all generated from these declarations.
// A new figure is one declaration in its procedure's *_figures.cpp (and its computation).
//
// A path is keys separated by dots; `name[*]` takes every element of an array. The figure at
// the end of a path is a number or an uncertain figure object ({"value", "expanded", ...});
// its uncertainty, when stated, is found beside it in its object's `uncertainty` object under
// the same key, or in the figure object itself (uncertainty_path says which, for readers).

#include <string_view>

#include "wavebench/strict_yaml/units.hpp"

namespace wavebench::figures {

// How a product spec bounds the figure (configs/specs/*.yaml, run limits).
enum class LimitKind {
  kNone,
  kUpper,             // the figure must not exceed the limit
  kLower,             // the figure must reach the limit (stiffness)
  kUpperOfMagnitude,  // |figure| must not exceed the limit (a mean TE of either sign)
};

struct SpecLimit {
  LimitKind kind = LimitKind::kNone;
  const char* key = "";  // run_limits key ("static_p2p_arcmin")
};

// The fleet view's trend of the figure: a typed column of fleet_runs in both stores. Several
// procedures may feed one trend (lost motion from the lost-motion and the torsional
// procedure): they name the same trend and column; the first declaration describes it.
struct FleetTrend {
  const char* name = "";    // what a user types ("k1"); "" when the figure is not trended
  const char* column = "";  // the column of fleet_runs ("k1_nm_per_rad")
  const char* what = "";    // the fleet page's description
};

// How the run page and the report show the figure.
enum class PlotKind {
  kValue,       // one row: value ± U
  kPerElement,  // one row per array element (the path has [*])
};

struct FigureDeclaration {
  const char* name;              // unique; the product spec key when limited ("hysteresis_loss")
  const char* procedure;         // the registry's procedure name; "*": any procedure (the twin's)
  const char* path;              // in results.json ("torsional.hysteresis_loss_arcmin")
  const char* uncertainty_path;  // where its uncertainty is; "" when none is stated
  const char* label;             // "Hysteresis loss"
  strict_yaml::Dimension dimension;
  const char* unit;          // of the figure in results.json and of its limit key ("arcmin")
  double per_unit;           // SI per `unit`
  const char* display_unit;  // what the page prints ("N·m/rad")
  double display_scale;      // displayed = value * display_scale
  int display_digits;        // significant digits a table prints
  SpecLimit limit;
  FleetTrend fleet;
  PlotKind plot;
};

inline bool is_limited(const FigureDeclaration& f) {
  return f.limit.kind != LimitKind::kNone;
}
inline bool is_trended(const FigureDeclaration& f) {
  return *f.fleet.name != '\0';
}

}  // namespace wavebench::figures
