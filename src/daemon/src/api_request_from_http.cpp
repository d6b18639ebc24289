#include "wavebench/daemon/api_request_from_http.hpp"

namespace wavebench::daemon {

namespace http = boost::beast::http;

ApiRequest api_request_from_http(const http::request<http::string_body>& request) {
  ApiRequest api;
  api.method = std::string(request.method_string());
  api.target = std::string(request.target());
  if (request.count(http::field::host) == 1) api.host = std::string(request[http::field::host]);
  api.authorization = std::string(request[http::field::authorization]);
  api.body = request.body();
  return api;
}

}  // namespace wavebench::daemon
