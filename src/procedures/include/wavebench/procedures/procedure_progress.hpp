#pragma once
// How a procedure tells its caller where it is: a phase name and the fraction of the procedure
// done (0..1). The run executor maps this onto the whole run.

#include <functional>
#include <string>

namespace wavebench::procedures {

using ProcedureProgress = std::function<void(const std::string& phase, double fraction)>;

}  // namespace wavebench::procedures
