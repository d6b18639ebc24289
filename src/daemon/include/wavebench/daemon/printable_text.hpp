#pragma once
// Text from a request (a path, a query value, a run id) echoed into an error message or a log
// line: anything that is not valid, printable UTF-8 is shown as \xNN, and long text is cut, so
// an answer can always be serialised as JSON and a log line stays one short line.

#include <cstddef>
#include <string>
#include <string_view>

namespace wavebench::daemon {

inline constexpr std::size_t kEchoLimit = 200;

// Valid UTF-8 without control characters passes unchanged (up to `limit` bytes, then
// "...(N bytes)"); each other byte becomes "\xNN".
std::string printable_text(std::string_view text, std::size_t limit = kEchoLimit);

// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code points past
// U+10FFFF).
bool is_valid_utf8(std::string_view text);

}  // namespace wavebench::daemon
