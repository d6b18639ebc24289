// The SDO client state machine against a hostile server: the input chooses the request (upload
// or a download of some length) and then every reply frame. The client must neither crash nor
// hang, and every transfer must complete exactly once.
#include <boost/asio/io_context.hpp>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "wavebench/can/virtual_can_bus.hpp"
#include "wavebench/canopen/sdo_client.hpp"

namespace wc = wavebench::can;
namespace co = wavebench::canopen;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  boost::asio::io_context io;
  wc::VirtualCanBus bus(io);
  bus.record(false);
  auto master = bus.endpoint("master");
  auto server = bus.endpoint("server");
  int completions = 0;
  int requests = 0;
  {
    co::SdoClient sdo(*master, 5, std::chrono::hours(1));  // timers never fire during a run
    std::size_t pos = 0;
    while (pos + 1 < size) {
      const std::uint8_t op = data[pos++];
      if ((op & 0x80) != 0 && requests < 8) {
        ++requests;
        if ((op & 0x40) != 0) {
          sdo.set_block_upload((op & 0x20) != 0, static_cast<std::uint8_t>(1 + (op & 0x03)));
          sdo.async_upload(0x2000, op & 0x0F, [&](std::error_code, std::vector<std::uint8_t> d) {
            ++completions;
            if (d.size() > (1U << 20)) std::abort();
          });
        } else {
          std::vector<std::uint8_t> payload(op & 0x3F, 0x5A);
          sdo.async_download(0x2000, 1, payload, [&](std::error_code) { ++completions; });
        }
        continue;
      }
      // A reply frame: length then bytes (replies for this node and, sometimes, another).
      wc::Frame f;
      f.id = (op & 0x01) != 0 ? 0x586U : 0x585U;
      f.len = static_cast<std::uint8_t>(data[pos++] % 9);
      for (std::size_t i = 0; i < f.len && pos < size; ++i) f.data[i] = data[pos++];
      sdo.on_frame(f);
      io.poll();
      io.restart();
    }
    if (completions > requests) std::abort();
  }
  // Destroying the client with transfers pending must not call their handlers afterwards.
  const int before = completions;
  io.restart();
  io.poll();
  if (completions != before) std::abort();
  return 0;
}
