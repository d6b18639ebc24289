#pragma once
// What a procedure had finished when its run was stopped (issue #22: an aborted run keeps
// every figure it had finished). A procedure that measures in parts (a static run's passes)
// hands one of these over after each part; the run keeps the last and, if the run does not
// complete, writes its sections into results.json marked as from an aborted run.

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

namespace wavebench::procedures {

struct FinishedFigures {
  // results.json's sections over the finished parts: computed when called, after the run on
  // the post-run worker (the analysis must not hold the bench's loop between two parts).
  std::function<nlohmann::json()> sections;
  int finished = 0;  // parts finished
  int planned = 0;   // parts the procedure planned
  std::string unit;  // what a part is ("passes")
};

// Called on the bench thread after each finished part: it must return quickly (no analysis,
// no I/O).
using FinishedFiguresSink = std::function<void(FinishedFigures)>;

}  // namespace wavebench::procedures
