#pragma once
// The token that guards everything that moves hardware: a random hex string in a file only its
// owner can read. Clients send it as `Authorization: Bearer <token>`.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace wavebench::daemon {

// 256 random bits from /dev/urandom as 64 hex digits: the token and the console's session ids.
std::string random_hex_token();

// A token shorter than this is guessable; the daemon refuses to start with one.
inline constexpr std::size_t kMinTokenLength = 16;
inline constexpr std::size_t kMaxTokenFileBytes = 4096;

// A token file the daemon will not use (group/other access, too short, not a regular file):
// a configuration error (exit 2), with the reason and the fix.
class TokenFileRefused : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Reads the token; creates the file (mode 0600, parent directories as needed) with a new
// random token when it is missing. An existing file must be a regular file of the daemon's
// user that no one else can read or write (mode 0600 or stricter), holding one token of at
// least kMinTokenLength printable characters: else TokenFileRefused. Throws
// std::runtime_error naming the path when the file cannot be read or created.
std::string load_or_create_token(const std::filesystem::path& path);
// Reads an existing token (the client side): a regular file of at most kMaxTokenFileBytes
// holding printable characters. Throws TokenFileRefused when the file is not that, and
// std::runtime_error when it cannot be read; both name the path.
std::string read_token(const std::filesystem::path& path);
// Whether an Authorization header value carries `token` (compared in constant time).
bool bearer_matches(std::string_view authorization, std::string_view token);
// Where both the daemon and the CLI look when no --token-file is given:
// $WAVEBENCH_TOKEN_FILE, else $HOME/.config/wavebench/daemon.token.
std::filesystem::path default_token_file();

}  // namespace wavebench::daemon
