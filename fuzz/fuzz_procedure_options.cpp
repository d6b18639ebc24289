// The procedure-options loader on arbitrary text. std::invalid_argument is its documented
// refusal; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "wavebench/procedures/procedure_options_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)wavebench::procedures::procedure_options_from_yaml(text, "fuzz.yaml");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
