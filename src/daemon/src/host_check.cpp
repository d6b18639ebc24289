#include "wavebench/daemon/host_check.hpp"

#include <boost/asio/ip/address.hpp>
#include <charconv>

namespace wavebench::daemon {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  for (auto& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

bool valid_port(std::string_view port) {
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  return !port.empty() && ec == std::errc() && end == port.data() + port.size() && value <= 65535;
}

// "name:port", "[v6]:port", "name" -> name (brackets removed); empty when malformed.
std::string host_name(std::string_view host) {
  if (host.empty()) return {};
  if (host.front() == '[') {
    const auto close = host.find(']');
    if (close == std::string_view::npos) return {};
    const auto rest = host.substr(close + 1);
    if (!rest.empty() && (rest.front() != ':' || !valid_port(rest.substr(1)))) return {};
    return std::string(host.substr(1, close - 1));
  }
  const auto colon = host.find(':');
  if (colon != std::string_view::npos) {
    if (!valid_port(host.substr(colon + 1))) return {};
    host = host.substr(0, colon);
  }
  return std::string(host);
}

}  // namespace

HostCheck::HostCheck(std::vector<std::string> allowed_names) {
  for (const auto& name : allowed_names) allowed_names_.push_back(lower(name));
}

bool HostCheck::allows(std::string_view host) const {
  const auto name = lower(host_name(host));
  if (name.empty()) return false;
  if (name == "localhost") return true;
  boost::system::error_code ec;
  const auto address = boost::asio::ip::make_address(name, ec);
  if (!ec) return !address.is_v6() || address.to_v6().scope_id() == 0;
  for (const auto& allowed : allowed_names_) {
    if (name == allowed) return true;
  }
  return false;
}

std::string HostCheck::expected() const {
  std::string text = "an IP address or localhost";
  for (const auto& name : allowed_names_) text += ", " + name;
  return text;
}

}  // namespace wavebench::daemon
