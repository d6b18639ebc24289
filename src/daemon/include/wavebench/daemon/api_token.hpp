#pragma once
// The token that guards everything that moves hardware: a random hex string in a file only its
// owner can read. Clients send it as `Authorization: Bearer <token>`.

#include <filesystem>
#include <string>
#include <string_view>

namespace wavebench::daemon {

// Reads the token; creates the file (mode 0600, parent directories as needed) with a new
// random token when it is missing. Throws std::runtime_error naming the path when the file is
// unreadable or empty.
std::string load_or_create_token(const std::filesystem::path& path);
// Reads an existing token (the client side). Throws std::runtime_error naming the path.
std::string read_token(const std::filesystem::path& path);
// Whether an Authorization header value carries `token` (compared in constant time).
bool bearer_matches(std::string_view authorization, std::string_view token);
// Where both the daemon and the CLI look when no --token-file is given:
// $WAVEBENCH_TOKEN_FILE, else $HOME/.config/wavebench/daemon.token.
std::filesystem::path default_token_file();

}  // namespace wavebench::daemon
