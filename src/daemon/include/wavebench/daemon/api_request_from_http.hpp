#pragma once
// A request as Beast parsed it, as the API sees it: one place, so the server and the HTTP
// fuzzer hand the API exactly the same thing.

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>

#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon {

// Host is left empty unless the request carries exactly one Host header: two could mean two
// different hosts to us and to a proxy.
ApiRequest api_request_from_http(
    const boost::beast::http::request<boost::beast::http::string_body>& request);

}  // namespace wavebench::daemon
