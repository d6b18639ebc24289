#pragma once
// SHA-256 (OpenSSL) of a text, as 64 lower-case hex digits: the config hash of a run.

#include <string>
#include <string_view>

namespace wavebench::storage {

std::string sha256_hex(std::string_view text);

}  // namespace wavebench::storage
