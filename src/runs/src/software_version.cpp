#include "wavebench/runs/software_version.hpp"

namespace wavebench::runs {

const char* software_version() {
  return WAVEBENCH_VERSION;
}

}  // namespace wavebench::runs
