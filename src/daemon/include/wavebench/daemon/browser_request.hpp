#pragma once
// What a browser's request carries that the API checks before it changes the bench
// (issue #10): the session cookie, the Origin, and the console's own request header.

#include <string>
#include <string_view>

namespace wavebench::daemon {

inline constexpr std::string_view kSessionCookie = "wb_session";
// A header a cross-site form cannot send, and a cross-origin fetch can send only after a CORS
// preflight, which this daemon never grants.
inline constexpr std::string_view kConsoleHeader = "X-Wavebench-Request";

// The value of cookie `name` in a Cookie header ("a=1; wb_session=..."); empty when absent.
std::string cookie_value(std::string_view cookie_header, std::string_view name);

// Whether an Origin header names this daemon as the browser reached it: "http://" + Host.
// (Host has passed host_check.hpp by then.) "null" and anything else are foreign.
bool same_origin(std::string_view origin, std::string_view host);

// The Set-Cookie value that sets (max_age_s > 0) or clears (0) the session.
std::string session_cookie(std::string_view id, long long max_age_s);

}  // namespace wavebench::daemon
