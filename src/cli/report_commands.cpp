// Placeholder until the owner of this area lands its subcommands (issue #5).
#include "commands.hpp"

namespace wavebench::cli {

void register_report_commands(CLI::App& /*app*/, ExitStatus& /*status*/) {}

}  // namespace wavebench::cli
