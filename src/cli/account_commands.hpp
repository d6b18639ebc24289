#pragma once
// `wavebench account hash|add` (account_commands.cpp): entries of wavebenchd's accounts file.

#include "commands.hpp"

namespace wavebench::cli {

void register_account_commands(CLI::App& app, ExitStatus& status);  // account hash|add

}  // namespace wavebench::cli
