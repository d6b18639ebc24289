#include "wavebench/bench/bench.hpp"

namespace wavebench::bench {

const char* lifecycle_name(BenchLifecycle state) {
  switch (state) {
    case BenchLifecycle::kUnconfigured:
      return "unconfigured";
    case BenchLifecycle::kReady:
      return "ready";
    case BenchLifecycle::kFault:
      return "fault";
  }
  return "?";
}

}  // namespace wavebench::bench
