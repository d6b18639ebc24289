#pragma once
// What a browser's request carries that the API checks before it changes the bench
// (issue #10): the session cookie, the Origin, and the console's own request header.

#include <string>
#include <string_view>

namespace wavebench::daemon {

// The session cookie's name is this prefix, '_' and the port the browser reached the daemon on
// (session_cookie_name). Browsers keep cookies per host, not per host and port: two daemons on
// one PC would otherwise overwrite each other's session at each login (issue #22). The port is
// what tells them apart and stays the same across a restart, so a restart alone never makes the
// operator log in under a new name (the sessions themselves end with the daemon).
inline constexpr std::string_view kSessionCookie = "wb_session";
// A header a cross-site form cannot send, and a cross-origin fetch can send only after a CORS
// preflight, which this daemon never grants.
inline constexpr std::string_view kConsoleHeader = "X-Wavebench-Request";

// The value of cookie `name` in a Cookie header ("a=1; wb_session=..."); empty when absent.
std::string cookie_value(std::string_view cookie_header, std::string_view name);

// Whether an Origin header names this daemon as the browser reached it: "http://" + Host.
// (Host has passed host_check.hpp by then.) "null" and anything else are foreign.
bool same_origin(std::string_view origin, std::string_view host);

// kSessionCookie + "_" + the port of `host` (a Host header: "name:port", "[v6]:port", or no port:
// 80). A port that is not 1 to 5 digits gives the prefix alone.
std::string session_cookie_name(std::string_view host);

// The Set-Cookie value that sets (max_age_s > 0) or clears (0) the session cookie `name`.
std::string session_cookie(std::string_view name, std::string_view id, long long max_age_s);

}  // namespace wavebench::daemon
