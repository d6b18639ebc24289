#include "wavebench/daemon/http_target.hpp"

#include <stdexcept>

namespace wavebench::daemon {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string url_decode(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '+') {
      out += ' ';
    } else if (c == '%') {
      const bool room = i + 2 < text.size();
      const int hi = room ? hex_value(text[i + 1]) : -1;
      const int lo = room ? hex_value(text[i + 2]) : -1;
      if (hi < 0 || lo < 0) {
        throw std::invalid_argument("target: bad %-escape in '" + std::string(text) + "'");
      }
      out += static_cast<char>(hi * 16 + lo);
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string url_encode(std::string_view text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') || u == '-' ||
        u == '_' || u == '.' || u == '~') {
      out += c;
    } else {
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 0xfu];
    }
  }
  return out;
}

HttpTarget parse_http_target(std::string_view target) {
  HttpTarget t;
  const auto question = target.find('?');
  const auto raw_path = target.substr(0, question);
  t.path = url_decode(raw_path);
  std::size_t start = 0;
  while (start <= raw_path.size()) {
    const auto slash = raw_path.find('/', start);
    const auto piece =
        raw_path.substr(start, slash == std::string_view::npos ? raw_path.npos : slash - start);
    if (!piece.empty()) t.segments.push_back(url_decode(piece));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  if (question == std::string_view::npos) return t;
  auto query = target.substr(question + 1);
  while (!query.empty()) {
    const auto amp = query.find('&');
    const auto pair = query.substr(0, amp);
    if (!pair.empty()) {
      const auto eq = pair.find('=');
      const auto key = url_decode(pair.substr(0, eq));
      const auto value =
          eq == std::string_view::npos ? std::string() : url_decode(pair.substr(eq + 1));
      t.query[key] = value;
    }
    if (amp == std::string_view::npos) break;
    query = query.substr(amp + 1);
  }
  return t;
}

}  // namespace wavebench::daemon
