#include "wavebench/procedures/software_version.hpp"

namespace wavebench::procedures {

const char* software_version() {
  return WAVEBENCH_VERSION;
}

}  // namespace wavebench::procedures
