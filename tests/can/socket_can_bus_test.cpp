// On a kernel without AF_CAN (this build host) opening must fail loudly, naming the interface.
#include "wavebench/can/socket_can_bus.hpp"

#include <gtest/gtest.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

namespace wavebench::can {
namespace {

TEST(SocketCanBus, MissingInterfaceOrMissingCanSupportIsAClearError) {
  boost::asio::io_context io;
  try {
    SocketCanBus bus(io, "wbnope0");
    FAIL() << "opening a nonexistent interface succeeded";
  } catch (const std::system_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("wbnope0"), std::string::npos) << what;
    const int fd = ::socket(PF_CAN, SOCK_RAW, 1);
    if (fd < 0) {
      EXPECT_NE(what.find("no CAN support"), std::string::npos) << what;
    } else {
      ::close(fd);
      EXPECT_NE(what.find("SIOCGIFINDEX"), std::string::npos) << what;
    }
  }
}

TEST(SocketCanBus, OverlongInterfaceNameIsRejected) {
  boost::asio::io_context io;
  EXPECT_THROW(SocketCanBus(io, std::string(IFNAMSIZ, 'x')), std::invalid_argument);
}

}  // namespace
}  // namespace wavebench::can
