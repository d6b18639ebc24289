#pragma once
// The version recorded with every run (results.json, the run index).

namespace wavebench::runs {

const char* software_version();

}  // namespace wavebench::runs
