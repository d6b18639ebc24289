#include "wavebench/daemon/http_server.hpp"

#include <linux/sockios.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <chrono>
#include <stdexcept>

#include "wavebench/daemon/api_request_from_http.hpp"
#include "wavebench/daemon/printable_text.hpp"

namespace wavebench::daemon {

namespace beast = boost::beast;
namespace http = beast::http;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

constexpr auto kIdleTimeout = std::chrono::seconds(60);

// A download's client must take each chunk within this; one that stops reading is dropped.
constexpr auto kChunkWriteDeadline = std::chrono::seconds(30);

// An event stream's socket keeps little unsent data: a client that stops reading fills it in
// seconds, not the minutes a socket buffer grown to megabytes would take.
constexpr int kEventSendBuffer = 64 << 10;

std::atomic<std::uint64_t> g_stalled_readers_dropped{0};

}  // namespace

std::uint64_t stalled_event_readers_dropped() {
  return g_stalled_readers_dropped.load();
}

ApiResponse parse_error_answer(beast::error_code ec) {
  if (ec == http::error::body_limit) {
    return api_error(413, "payload too large", "the request body is over 1 MiB");
  }
  if (ec == http::error::header_limit) {
    return api_error(431, "request header fields too large", "the request's header is over 16 KiB");
  }
  return api_error(400, "bad request", "not an HTTP/1.1 request we take (" + ec.message() + ")");
}

namespace {

class Session : public std::enable_shared_from_this<Session> {
 public:
  Session(tcp::socket socket, std::shared_ptr<const HttpServer::Handler> handler)
      : stream_(std::move(socket)), handler_(std::move(handler)) {}

  void start() {
    net::dispatch(stream_.get_executor(), [self = shared_from_this()] { self->read(); });
  }

 private:
  void read() {
    parser_.emplace();
    parser_->body_limit(kRequestBodyLimit);
    parser_->header_limit(kRequestHeaderLimit);
    stream_.expires_after(kIdleTimeout);
    http::async_read(
        stream_, buffer_, *parser_,
        [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
  }

  void on_read(beast::error_code ec) {
    if (ec == http::error::end_of_stream) {
      close();
      return;
    }
    if (ec && ec.category() == beast::http::make_error_code(http::error::bad_target).category()) {
      respond(parse_error_answer(ec), false, 11);
      return;
    }
    if (ec) return;  // timeout or reset: nothing to answer
    const auto& request = parser_->get();
    ApiRequest api = api_request_from_http(request);
    beast::error_code peer_error;
    const auto peer = stream_.socket().remote_endpoint(peer_error);
    if (!peer_error) api.client = peer.address().to_string();  // login rate limits per client
    ApiResponse response;
    try {
      response = (*handler_)(api);
    } catch (...) {
      response = api_error(500, "internal error", "the handler failed");
    }
    if (response.status >= 400) {
      const auto detail =
          response.body.is_object() ? response.body.find("detail") : response.body.end();
      spdlog::debug("{} {} -> {} {}", printable_text(api.method), printable_text(api.target),
                    response.status,
                    detail != response.body.end() && detail->is_string()
                        ? printable_text(detail->get<std::string>())
                        : std::string());
    }
    respond(std::move(response), request.keep_alive(), request.version());
  }

  void respond(ApiResponse response, bool keep_alive, unsigned version) {
    if (response.stream) {
      stream_events(std::move(response), version);
      return;
    }
    if (response.chunks) {
      send_chunks(std::move(response), version);
      return;
    }
    auto message = std::make_shared<http::response<http::string_body>>(
        static_cast<http::status>(response.status), version);
    message->set(http::field::server, "wavebenchd");
    message->set(http::field::content_type, response.content_type);
    message->set("X-Content-Type-Options", "nosniff");
    for (const auto& [name, value] : response.headers) message->set(name, value);
    message->keep_alive(keep_alive);
    message->body() =
        response.raw_body ? std::move(*response.raw_body) : response_text(response) + "\n";
    message->prepare_payload();
    http::async_write(stream_, *message,
                      [self = shared_from_this(), message](beast::error_code ec, std::size_t) {
                        if (ec) return;
                        if (!message->keep_alive()) {
                          self->close();
                          return;
                        }
                        self->read();
                      });
  }

  // The header of a response whose body follows in pieces (events, chunks).
  static std::shared_ptr<http::response<http::empty_body>> header_of(const ApiResponse& response,
                                                                     unsigned version) {
    auto header = std::make_shared<http::response<http::empty_body>>(
        static_cast<http::status>(response.status), version);
    header->set(http::field::server, "wavebenchd");
    header->set(http::field::content_type, response.content_type);
    header->set(http::field::cache_control, "no-store");
    header->set("X-Content-Type-Options", "nosniff");
    for (const auto& [name, value] : response.headers) header->set(name, value);
    return header;
  }

  // Server-sent events: the header without a length, then each event as the stream gives it,
  // until a write fails (the client went away) or the stream ends; then the connection closes.
  void stream_events(ApiResponse response, unsigned version) {
    events_ = std::move(response.stream);
    auto header = header_of(response, version);
    header->keep_alive(false);
    auto serializer = std::make_shared<http::response_serializer<http::empty_body>>(*header);
    beast::error_code ignored;
    stream_.socket().set_option(net::socket_base::send_buffer_size(kEventSendBuffer), ignored);
    stream_.expires_never();
    http::async_write_header(
        stream_, *serializer,
        [self = shared_from_this(), header, serializer](beast::error_code ec, std::size_t) {
          if (ec) return self->close();
          self->next_event();
        });
  }

  void next_event() {
    stream_.expires_never();
    timer_.expires_after(events_->period());
    timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      auto event = self->events_->next();
      if (!event) return self->close();
      if (event->empty()) return self->next_event();
      if (self->reader_stalled()) return self->drop_stalled_reader();
      self->event_ = std::move(*event);
      // A client that stops reading loses its slot instead of holding it for ever.
      self->stream_.expires_after(kStalledReaderLimit);
      net::async_write(self->stream_, net::buffer(self->event_),
                       [self](beast::error_code write_ec, std::size_t) {
                         if (write_ec == beast::error::timeout) return self->drop_stalled_reader();
                         if (write_ec) return self->close();
                         self->next_event();
                       });
    });
  }

  // Its queue full or unacknowledged for kStalledReaderLimit: the client is not reading.
  void drop_stalled_reader() {
    const auto dropped = ++g_stalled_readers_dropped;
    spdlog::warn(
        "live stream: the client read nothing for {} s; dropped, its slot freed "
        "({} dropped since start)",
        std::chrono::duration_cast<std::chrono::seconds>(kStalledReaderLimit).count(), dropped);
    events_.reset();  // frees the slot now, not when the socket has drained
    beast::error_code ignored;
    stream_.socket().close(ignored);
  }

  // Whether the client has left sent data unacknowledged (its receive window closed: it is not
  // reading) at every check for kStalledReaderLimit. A client that reads acknowledges within
  // a round trip, so its queue is empty again between two events.
  bool reader_stalled() {
    int queued = 0;
    if (::ioctl(stream_.socket().native_handle(), SIOCOUTQ, &queued) != 0 || queued <= 0) {
      stalled_since_.reset();
      return false;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!stalled_since_) stalled_since_ = now;
    return now - *stalled_since_ >= kStalledReaderLimit;
  }

  // A body made chunk by chunk (body_chunks.hpp): one chunk in memory at a time, each written
  // within kChunkWriteDeadline.
  void send_chunks(ApiResponse response, unsigned version) {
    chunks_ = std::move(response.chunks);
    auto header = header_of(response, version);
    header->chunked(true);
    header->keep_alive(false);
    auto serializer = std::make_shared<http::response_serializer<http::empty_body>>(*header);
    stream_.expires_after(kChunkWriteDeadline);
    http::async_write_header(
        stream_, *serializer,
        [self = shared_from_this(), header, serializer](beast::error_code ec, std::size_t) {
          if (ec) return self->end_chunks(false);
          self->next_chunk();
        });
  }

  void next_chunk() {
    std::optional<std::string> chunk;
    try {
      chunk = chunks_->next();
    } catch (const std::exception& e) {
      spdlog::warn("download cut short: {}", printable_text(e.what()));
      return end_chunks(false);
    }
    stream_.expires_after(kChunkWriteDeadline);
    if (!chunk) {
      net::async_write(stream_, http::make_chunk_last(),
                       [self = shared_from_this()](beast::error_code ec, std::size_t) {
                         self->end_chunks(!ec);
                       });
      return;
    }
    chunk_ = std::move(*chunk);
    net::async_write(stream_, http::make_chunk(net::buffer(chunk_)),
                     [self = shared_from_this()](beast::error_code ec, std::size_t) {
                       if (ec) return self->end_chunks(false);
                       self->next_chunk();
                     });
  }

  // Frees the body (its download slot, its scratch file) at once. A body that failed or whose
  // client went away ends with a reset, never the last chunk: the client sees it incomplete.
  void end_chunks(bool complete) {
    chunks_.reset();
    chunk_.clear();
    chunk_.shrink_to_fit();
    beast::error_code ignored;
    if (complete) {
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    } else {
      stream_.socket().close(ignored);
    }
  }

  void close() {
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<const HttpServer::Handler> handler_;
  std::shared_ptr<EventStream> events_;
  net::steady_timer timer_{stream_.get_executor()};
  std::string event_;
  std::optional<std::chrono::steady_clock::time_point> stalled_since_;
  std::shared_ptr<BodyChunks> chunks_;
  std::string chunk_;
};

}  // namespace

struct HttpServer::Impl : std::enable_shared_from_this<HttpServer::Impl> {
  Impl(net::io_context& io, Handler h)
      : io_context(io),
        acceptor(net::make_strand(io)),
        handler(std::make_shared<const Handler>(std::move(h))) {}

  void accept() {
    acceptor.async_accept(net::make_strand(io_context),
                          [self = shared_from_this()](beast::error_code ec, tcp::socket socket) {
                            if (ec == net::error::operation_aborted || !self->acceptor.is_open()) {
                              return;
                            }
                            if (!ec)
                              std::make_shared<Session>(std::move(socket), self->handler)->start();
                            self->accept();
                          });
  }

  net::io_context& io_context;
  tcp::acceptor acceptor;
  std::shared_ptr<const Handler> handler;
  unsigned short port = 0;
};

HttpServer::HttpServer(net::io_context& io, const std::string& address, unsigned short port,
                       Handler handler)
    : impl_(std::make_shared<Impl>(io, std::move(handler))) {
  beast::error_code ec;
  const auto ip = net::ip::make_address(address, ec);
  if (ec) {
    throw std::runtime_error("listen: address '" + address + "' is not an IP address (" +
                             ec.message() + ")");
  }
  const tcp::endpoint endpoint(ip, port);
  auto& acceptor = impl_->acceptor;
  const auto fail = [&](const char* what) {
    throw std::runtime_error("listen: cannot " + std::string(what) + " " + address + ":" +
                             std::to_string(port) + " (" + ec.message() + ")");
  };
  acceptor.open(endpoint.protocol(), ec);
  if (ec) fail("open");
  acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (ec) fail("configure");
  acceptor.bind(endpoint, ec);
  if (ec) fail("bind");
  acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec) fail("listen on");
  impl_->port = acceptor.local_endpoint(ec).port();
}

HttpServer::~HttpServer() {
  stop();
}

unsigned short HttpServer::port() const {
  return impl_->port;
}

void HttpServer::start() {
  impl_->accept();
}

void HttpServer::stop() {
  net::post(impl_->acceptor.get_executor(), [impl = impl_] {
    beast::error_code ignored;
    impl->acceptor.close(ignored);
  });
}

}  // namespace wavebench::daemon
