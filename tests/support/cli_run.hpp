#pragma once
// Runs the `wavebench` binary (WAVEBENCH_CLI, set by the test's CMakeLists) through the shell
// with stdout and stderr captured in `log`: for tests of exit statuses and printed messages.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace wavebench::testing {

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

inline CliRun run_cli(const std::string& args, const std::filesystem::path& log) {
  const std::string cmd =
      std::string("'") + WAVEBENCH_CLI + "' " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

}  // namespace wavebench::testing
