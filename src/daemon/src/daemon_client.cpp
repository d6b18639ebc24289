#include "wavebench/daemon/daemon_client.hpp"

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <thread>

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
                           std::chrono::milliseconds timeout,
                           std::chrono::milliseconds connect_timeout)
    : endpoint_(parse_daemon_url(url)),
      token_(std::move(token)),
      timeout_(timeout),
      connect_timeout_(connect_timeout) {}

DaemonReply DaemonClient::get(const std::string& target) const {
  const auto until = std::chrono::steady_clock::now() + busy_for_;
  auto pause = std::chrono::milliseconds(250);
  for (;;) {
    auto reply = request(false, target, "");
    if (reply.status != 503 || busy_for_.count() <= 0) return reply;
    const auto now = std::chrono::steady_clock::now();
    auto wait =
        reply.retry_after_s >= 0 ? std::chrono::milliseconds(reply.retry_after_s * 1000) : pause;
    wait = std::max(wait, std::chrono::milliseconds(100));
    if (now + wait > until) return reply;  // waited long enough: the caller reports the 503
    if (busy_notice_) {
      busy_notice_(
          "the daemon is busy (" + reply.error_text() + "); retrying " + target + " in " +
          std::to_string(wait.count()) + " ms, for at most " +
          std::to_string(std::chrono::duration_cast<std::chrono::seconds>(until - now).count()) +
          " s more");
    }
    std::this_thread::sleep_for(wait);
    pause = std::min(pause * 2, std::chrono::milliseconds(4000));
  }
}

DaemonReply DaemonClient::post(const std::string& target, const nlohmann::json& body) const {
  return request(true, target, body.dump());
}

DaemonReply DaemonClient::request(bool post, const std::string& target,
                                  const std::string& body) const {
  const std::string where = "http://" + endpoint_.host + ":" + endpoint_.port;
  // Asynchronous operations with a deadline: Beast's stream timeouts do not apply to its
  // blocking calls, and a silent server must not hang the CLI.
  net::io_context io;
  tcp::resolver resolver(io);
  beast::tcp_stream stream(io);
  http::request<http::string_body> req(post ? http::verb::post : http::verb::get, target, 11);
  req.set(http::field::host, endpoint_.host.find(':') != std::string::npos
                                 ? "[" + endpoint_.host + "]:" + endpoint_.port
                                 : endpoint_.host + ":" + endpoint_.port);
  req.set(http::field::user_agent, "wavebench");
  if (!token_.empty()) req.set(http::field::authorization, "Bearer " + token_);
  if (post) {
    req.set(http::field::content_type, "application/json");
    req.body() = body;
  }
  req.keep_alive(false);
  req.prepare_payload();

  beast::flat_buffer buffer;
  http::response_parser<http::string_body> parser;
  parser.body_limit(kMaxReplyBytes);
  beast::error_code failure;
  const char* stage = "connect";
  const auto fail = [&](beast::error_code ec, const char* at) {
    failure = ec;
    stage = at;
  };
  resolver.async_resolve(
      endpoint_.host, endpoint_.port, [&](beast::error_code ec, tcp::resolver::results_type r) {
        if (ec) return fail(ec, "resolve");
        stream.expires_after(connect_timeout_);
        stream.async_connect(r, [&](beast::error_code ec2, const tcp::endpoint&) {
          if (ec2) return fail(ec2, "connect");
          stream.expires_after(timeout_);
          http::async_write(stream, req, [&](beast::error_code ec3, std::size_t) {
            if (ec3) return fail(ec3, "send");
            http::async_read(stream, buffer, parser, [&](beast::error_code ec4, std::size_t) {
              if (ec4) return fail(ec4, "answer");
              beast::error_code ignored;
              stream.socket().shutdown(tcp::socket::shutdown_both, ignored);
            });
          });
        });
      });
  io.run();
  if (failure) {
    const bool timed_out = failure == beast::error::timeout;
    throw DaemonUnreachable(
        "no daemon answering at " + where + " (" + stage + ": " +
        (timed_out ? std::string("no answer within ") +
                         std::to_string(
                             (std::string_view(stage) == "connect" ? connect_timeout_ : timeout_)
                                 .count()) +
                         " ms"
                   : failure.message()) +
        "); is wavebenchd running? (--daemon URL)");
  }
  DaemonReply reply;
  reply.status = static_cast<int>(parser.get().result_int());
  const auto retry_after = parser.get()[http::field::retry_after];
  if (!retry_after.empty() && retry_after.size() <= 4 &&
      retry_after.find_first_not_of("0123456789") == std::string_view::npos) {
    reply.retry_after_s = std::stoi(std::string(retry_after));  // seconds; an HTTP date: none
  }
  const auto& text = parser.get().body();
  reply.body = nlohmann::json::parse(text, nullptr, false);
  // Every answer of the daemon, errors included, is a JSON object: anything else is not it.
  if (reply.body.is_discarded() || !reply.body.is_object()) {
    throw DaemonUnreachable("the answer from " + where + " is not the daemon's JSON (HTTP " +
                            std::to_string(reply.status) + ", " + std::to_string(text.size()) +
                            " bytes of " +
                            std::string(parser.get()[http::field::content_type].empty()
                                            ? "no content type"
                                            : parser.get()[http::field::content_type]) +
                            "); is --daemon the wavebenchd API?");
  }
  return reply;
}

}  // namespace wavebench::daemon
