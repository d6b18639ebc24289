// Placeholder: the owning area replaces this file with its subcommands.
#include "commands.hpp"

namespace wavebench::cli {

void register_simbench_commands(CLI::App& /*app*/, ExitStatus& /*status*/) {}

}  // namespace wavebench::cli
