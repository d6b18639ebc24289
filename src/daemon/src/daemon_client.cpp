#include "wavebench/daemon/daemon_client.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

namespace wavebench::daemon {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

DaemonEndpoint parse_daemon_url(const std::string& url) {
  std::string rest = url;
  if (rest.rfind("http://", 0) == 0) {
    rest = rest.substr(7);
  } else if (rest.find("://") != std::string::npos) {
    throw std::invalid_argument("--daemon: got '" + url +
                                "', expected http://HOST:PORT (no TLS: the API is local)");
  }
  while (!rest.empty() && rest.back() == '/') rest.pop_back();
  DaemonEndpoint e;
  const auto colon = rest.rfind(':');
  if (colon == std::string::npos) {
    e.host = rest;
    e.port = "8470";
  } else {
    e.host = rest.substr(0, colon);
    e.port = rest.substr(colon + 1);
  }
  if (e.host.size() > 2 && e.host.front() == '[' && e.host.back() == ']') {
    e.host = e.host.substr(1, e.host.size() - 2);
  }
  const bool port_ok = !e.port.empty() && e.port.size() <= 5 &&
                       e.port.find_first_not_of("0123456789") == std::string::npos &&
                       std::stoul(e.port) > 0 && std::stoul(e.port) < 65536;
  if (e.host.empty() || !port_ok || rest.find('/') != std::string::npos) {
    throw std::invalid_argument("--daemon: got '" + url + "', expected http://HOST:PORT");
  }
  return e;
}

std::string DaemonReply::error_text() const {
  if (body.is_object() && body.contains("error")) {
    std::string text = body.value("error", "");
    const auto detail = body.value("detail", "");
    if (!detail.empty()) text += ": " + detail;
    return text;
  }
  return "HTTP " + std::to_string(status);
}

DaemonClient::DaemonClient(const std::string& url, std::string token,
                           std::chrono::milliseconds timeout)
    : endpoint_(parse_daemon_url(url)), token_(std::move(token)), timeout_(timeout) {}

DaemonReply DaemonClient::get(const std::string& target) const {
  return request(false, target, "");
}

DaemonReply DaemonClient::post(const std::string& target, const nlohmann::json& body) const {
  return request(true, target, body.dump());
}

DaemonReply DaemonClient::request(bool post, const std::string& target,
                                  const std::string& body) const {
  const std::string where = "http://" + endpoint_.host + ":" + endpoint_.port;
  try {
    net::io_context io;
    tcp::resolver resolver(io);
    beast::tcp_stream stream(io);
    const auto endpoints = resolver.resolve(endpoint_.host, endpoint_.port);
    stream.expires_after(timeout_);
    stream.connect(endpoints);

    http::request<http::string_body> req(post ? http::verb::post : http::verb::get, target, 11);
    req.set(http::field::host, endpoint_.host);
    req.set(http::field::user_agent, "wavebench");
    if (!token_.empty()) req.set(http::field::authorization, "Bearer " + token_);
    if (post) {
      req.set(http::field::content_type, "application/json");
      req.body() = body;
    }
    req.keep_alive(false);
    req.prepare_payload();
    stream.expires_after(timeout_);
    http::write(stream, req);

    beast::flat_buffer buffer;
    http::response_parser<http::string_body> parser;
    parser.body_limit(256u << 20);
    stream.expires_after(timeout_);
    http::read(stream, buffer, parser);
    beast::error_code ignored;
    stream.socket().shutdown(tcp::socket::shutdown_both, ignored);

    DaemonReply reply;
    reply.status = static_cast<int>(parser.get().result_int());
    reply.body = nlohmann::json::parse(parser.get().body(), nullptr, false);
    if (reply.body.is_discarded()) reply.body = nullptr;
    return reply;
  } catch (const beast::system_error& e) {
    throw DaemonUnreachable("no daemon answering at " + where + " (" + e.code().message() +
                            "); is wavebenchd running? (--daemon URL)");
  }
}

}  // namespace wavebench::daemon
