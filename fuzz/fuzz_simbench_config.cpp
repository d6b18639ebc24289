// The simulated-bench device config on arbitrary text. std::invalid_argument is its
// documented refusal; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "wavebench/simdevices/simulated_bench_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)wavebench::simdevices::parse_simulated_bench_config(text);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
