#pragma once
// Raw bytes to an HTTP server on loopback and what came back, for requests no well-behaved
// client would send (bad bytes in the target, oversized or NUL-containing headers, a foreign
// Host). A receive timeout bounds every call.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <string>

namespace wavebench::testing {

struct RawReply {
  bool answered = false;  // an HTTP status line came back
  int status = 0;
  std::string body;
  nlohmann::json json;  // discarded when the body is not JSON
};

inline RawReply raw_http(unsigned short port, const std::string& bytes, int timeout_s = 10) {
  RawReply r;
  r.json = nlohmann::json(nlohmann::json::value_t::discarded);
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return r;
  timeval tv{timeout_s, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return r;
  }
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const auto n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the server may answer and close before reading everything
    sent += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_WR);
  std::string reply;
  char buffer[65536];
  for (;;) {
    const auto n = ::recv(fd, buffer, sizeof buffer, 0);
    if (n <= 0) break;
    reply.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (reply.rfind("HTTP/1.", 0) != 0 || reply.size() < 12) return r;
  r.answered = true;
  r.status = std::stoi(reply.substr(9, 3));
  const auto head_end = reply.find("\r\n\r\n");
  if (head_end != std::string::npos) r.body = reply.substr(head_end + 4);
  r.json = nlohmann::json::parse(r.body, nullptr, false);
  return r;
}

// A GET with the given target and Host, closing the connection after the answer.
inline std::string get_request(const std::string& target, const std::string& host,
                               const std::string& extra_headers = "") {
  return "GET " + target + " HTTP/1.1\r\nHost: " + host + "\r\n" + extra_headers +
         "Connection: close\r\n\r\n";
}

inline std::string post_request(const std::string& target, const std::string& host,
                                const std::string& body, const std::string& token) {
  return "POST " + target + " HTTP/1.1\r\nHost: " + host +
         "\r\nContent-Type: application/json\r\nAuthorization: Bearer " + token +
         "\r\nContent-Length: " + std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" +
         body;
}

}  // namespace wavebench::testing
