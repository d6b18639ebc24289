// The CiA 306 EDS/DCF reader on arbitrary bytes, as Eds::load reads a file. EdsError is the
// documented refusal; anything else is a finding. What was read is used as a caller would:
// every object's values, every warning and problem.
#include <cstddef>
#include <cstdint>
#include <string>

#include "wavebench/canopen/eds.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using wavebench::canopen::Eds;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto eds = Eds::parse(text, "fuzz.eds");
    std::size_t seen = 0;
    for (const auto& [key, o] : eds.objects()) {
      seen += eds.default_integer(o, 127).has_value();
      seen += eds.default_unsigned(o, 127).has_value();
      seen += eds.problem(o.index, o.sub).has_value();
    }
    for (const auto& w : eds.warnings()) seen += w.size();
    (void)eds.vendor_number();
    (void)eds.commissioning();
    (void)seen;
  } catch (const wavebench::canopen::EdsError&) {
  }
  return 0;
}
