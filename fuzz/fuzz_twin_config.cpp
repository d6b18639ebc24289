// The twin-case loader on arbitrary text. config::ConfigError is its documented refusal;
// anything else (std::bad_alloc, another exception, a crash, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wavebench/config/config_error.hpp"
#include "wavebench/config/twin_case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)wavebench::config::parse_twin_case(text, "fuzz.yaml");
  } catch (const wavebench::config::ConfigError&) {
  }
  return 0;
}
