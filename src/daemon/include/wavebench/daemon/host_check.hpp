#pragma once
// DNS rebinding defence: a browser page from another site that resolves its own name to
// 127.0.0.1 still sends that name in Host. The daemon answers only requests whose Host is an
// IP literal (a browser sends one only when it connected to that address), "localhost", or a
// name the operator allowed.

#include <string>
#include <string_view>
#include <vector>

namespace wavebench::daemon {

class HostCheck {
 public:
  explicit HostCheck(std::vector<std::string> allowed_names = {});
  // `host` is the Host header as sent ("127.0.0.1:8470", "[::1]:8470", "localhost").
  bool allows(std::string_view host) const;
  // For the 4xx answer: what would have been accepted.
  std::string expected() const;

 private:
  std::vector<std::string> allowed_names_;  // lower case
};

}  // namespace wavebench::daemon
