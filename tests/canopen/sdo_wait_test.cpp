// Waits that keep exceptions: an SDO completion handler's exception reaches the waiting caller
// with its message (issue 23), and a coroutine suspends on a transfer instead of pumping a loop.
#include <gtest/gtest.h>

#include <boost/asio/co_spawn.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <exception>
#include <stdexcept>
#include <string>

#include "scripted_peer.hpp"
#include "wavebench/can/event_loop.hpp"
#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wavebench::canopen {
namespace {

using testing::ScriptedPeer;

struct SdoWaitFixture : ::testing::Test {
  boost::asio::io_context io;
  can::VirtualCanBus bus{io};
  std::unique_ptr<can::VirtualCanEndpoint> master = bus.endpoint("master");
  ScriptedPeer peer{bus};
  SdoClient sdo{*master, 1, std::chrono::milliseconds(50)};

  std::string message_of(const std::exception_ptr& failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      return e.what();
    }
  }
};

TEST_F(SdoWaitFixture, HandlerExceptionReachesTheThrowingCallerWithItsMessage) {
  peer.expect("601#4018100100000000", {"581#4318100178563412"});
  peer.expect("601#4018100200000000", {"581#4318100204030201"});
  sdo.async_upload(0x1018, 1, [](std::error_code, std::vector<std::uint8_t>) {
    throw std::runtime_error("xyz");
  });
  try {
    sdo.read<std::uint32_t>(0x1018, 2);
    FAIL() << "the handler's exception did not reach the waiting caller";
  } catch (const SdoError& e) {
    FAIL() << "rewritten into an SDO error: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "xyz");
  }
  // The queue went on: the client serves the next request.
  peer.expect("601#4018100200000000", {"581#4318100204030201"});
  EXPECT_EQ(sdo.read<std::uint32_t>(0x1018, 2), 0x01020304U);
  EXPECT_TRUE(peer.done());
}

TEST_F(SdoWaitFixture, HandlerExceptionIsNotAnErrorCodeOfTheTransfer) {
  peer.expect("601#4018100100000000", {"581#4318100178563412"});
  sdo.async_upload(0x1018, 1, [](std::error_code ec, std::vector<std::uint8_t>) {
    if (!ec) throw std::runtime_error("xyz");
  });
  std::error_code ec;
  EXPECT_THROW(
      {
        try {
          sdo.upload(0x1000, 0, ec);
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "xyz");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_FALSE(ec) << ec.message();
}

TEST_F(SdoWaitFixture, CoroutineSuspendsOnTransfersAndItsExceptionKeepsItsMessage) {
  peer.expect("601#4018100100000000", {"581#4318100178563412"});
  peer.expect("601#2B171000A00F0000", {"581#6017100000000000"});
  std::vector<std::uint8_t> vendor;
  std::error_code download_ec = make_error_code(SdoAbort::general);
  std::exception_ptr failure;
  bool finished = false;
  boost::asio::co_spawn(
      io,
      [&]() -> boost::asio::awaitable<void> {
        auto [ec, data] = co_await sdo.async_upload(0x1018, 1, boost::asio::use_awaitable);
        EXPECT_FALSE(ec) << ec.message();
        vendor = data;
        std::vector<std::uint8_t> heartbeat_ms{0xA0, 0x0F};  // 4000
        download_ec =
            co_await sdo.async_download(0x1017, 0, heartbeat_ms, boost::asio::use_awaitable);
        throw std::runtime_error("xyz");
      },
      [&](std::exception_ptr e) {
        failure = e;
        finished = true;
      });
  ASSERT_TRUE(can::run_until(io, [&] { return finished; }));
  EXPECT_EQ(vendor, (std::vector<std::uint8_t>{0x78, 0x56, 0x34, 0x12}));
  EXPECT_FALSE(download_ec) << download_ec.message();
  ASSERT_TRUE(failure);
  EXPECT_EQ(message_of(failure), "xyz");
  EXPECT_TRUE(peer.done());
}

TEST_F(SdoWaitFixture, AnotherHandlersExceptionLeavesADriveCallUnchanged) {
  // Before issue 23 the drive's wait swallowed it; now the caller learns what failed.
  Cia402Options options;
  Cia402Drive drive(sdo, options);
  boost::asio::steady_timer trouble(io, std::chrono::milliseconds(1));
  trouble.async_wait([](const boost::system::error_code&) { throw std::runtime_error("xyz"); });
  peer.expect("601#4041600000000000");  // statusword read: never answered before the throw
  std::error_code ec;
  try {
    drive.statusword(ec);
    FAIL() << "the other handler's exception was swallowed";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "xyz");
  }
}

}  // namespace
}  // namespace wavebench::canopen
