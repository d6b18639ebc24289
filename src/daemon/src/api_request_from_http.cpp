#include "wavebench/daemon/api_request_from_http.hpp"

#include "wavebench/daemon/browser_request.hpp"

namespace wavebench::daemon {

namespace http = boost::beast::http;

ApiRequest api_request_from_http(const http::request<http::string_body>& request) {
  ApiRequest api;
  api.method = std::string(request.method_string());
  api.target = std::string(request.target());
  if (request.count(http::field::host) == 1) api.host = std::string(request[http::field::host]);
  api.authorization = std::string(request[http::field::authorization]);
  api.body = request.body();
  api.cookie = std::string(request[http::field::cookie]);
  api.has_origin = request.count(http::field::origin) > 0;
  // Two Origin headers are one too many: kept as an empty, foreign, origin.
  if (request.count(http::field::origin) == 1)
    api.origin = std::string(request[http::field::origin]);
  api.console_request =
      std::string(request[boost::beast::string_view(kConsoleHeader.data(), kConsoleHeader.size())]);
  return api;
}

}  // namespace wavebench::daemon
