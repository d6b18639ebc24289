// Prints every declared figure (src/figures) as JSON, for results_schema_test.py: each
// declaration's path must resolve in a real results.json of its procedure and in the schema.
#include <iostream>

#include "wavebench/figures/figure_registry.hpp"

int main() {
  std::cout << wavebench::figures::all_figures_json().dump(2) << "\n";
  return 0;
}
