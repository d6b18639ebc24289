#pragma once
// The version and the commit recorded with every run (results.json, the run index) and named
// by `wavebench --version`, `wavebenchd --version` and /api/status.

namespace wavebench::procedures {

const char* software_version();  // the project's version, "0.1.0"
const char* software_commit();   // "<12 hex>", "<12 hex>+dirty" or "unknown"

}  // namespace wavebench::procedures
