// The bench-config loader on arbitrary text (relative paths resolve against configs/benches,
// as for the shipped configs the corpus starts from). config::ConfigError is its documented
// refusal; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wavebench/bench/bench_config.hpp"
#include "wavebench/config/config_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)wavebench::bench::parse_bench_config(text, WAVEBENCH_FUZZ_BENCHES_DIR, "fuzz.yaml");
  } catch (const wavebench::config::ConfigError&) {
  }
  return 0;
}
