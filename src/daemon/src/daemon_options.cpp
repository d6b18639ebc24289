#include "wavebench/daemon/daemon_options.hpp"

#include <boost/asio/ip/address.hpp>
#include <charconv>
#include <stdexcept>

namespace wavebench::daemon {

ListenAddress parse_listen_address(const std::string& text) {
  const auto fail = [&] {
    return std::invalid_argument("--listen: got '" + text +
                                 "', expected HOST:PORT with a port 0..65535 (e.g. "
                                 "127.0.0.1:8470)");
  };
  const auto colon = text.rfind(':');
  if (colon == std::string::npos) throw fail();
  ListenAddress a;
  std::string host = text.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  if (!host.empty()) a.host = host;
  const std::string port = text.substr(colon + 1);
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || ec != std::errc() || end != port.data() + port.size() || value > 65535) {
    throw fail();
  }
  a.port = static_cast<unsigned short>(value);
  boost::system::error_code address_error;
  boost::asio::ip::make_address(a.host, address_error);
  if (address_error) {
    throw std::invalid_argument("--listen: got '" + text + "', expected an IP address as HOST ('" +
                                a.host + "' is not one; e.g. 127.0.0.1:8470 or [::1]:8470)");
  }
  return a;
}

bool is_loopback(const ListenAddress& address) {
  boost::system::error_code ec;
  const auto ip = boost::asio::ip::make_address(address.host, ec);
  return !ec && ip.is_loopback();
}

}  // namespace wavebench::daemon
