// The Python peers of other test suites use /usr/bin/python3 with python3-can's socketcan
// interface; this checks that stack against our raw socket on the VM's vcan0 in both directions.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "can_raw_socket.hpp"
#include "can_utils_process.hpp"
#include "vcan_fixture.hpp"

namespace wavebench::vcan_smoke {
namespace {

using PythonCanOnVcan = VcanTest;

// Python starts slowly under emulation; this is only a guard against a hang.
constexpr std::chrono::milliseconds kPythonLimit{180000};

constexpr const char* kPeer = R"PY(
import can, sys
with can.Bus(interface="socketcan", channel="vcan0") as bus:
    bus.send(can.Message(arbitration_id=0x18FF50E5, is_extended_id=True, data=[1, 2, 3]))
    m = bus.recv(timeout=180)
    if m is None:
        sys.exit("no frame")
    print(f"{m.arbitration_id:X} {int(m.is_extended_id)} {int(m.is_remote_frame)} {m.data.hex()}")
)PY";

TEST_F(PythonCanOnVcan, PythonCanPeerExchangesFramesWithRawSocket) {
  ASSERT_EQ(run_command("/usr/bin/python3 -c 'import can'").exit_status, 0)
      << "/usr/bin/python3 cannot import can (python3-can)";
  CanRawSocket socket(kVcan);
  const std::string script_path =
      "/tmp/wavebench_vcan_smoke_peer_" + std::to_string(::getpid()) + ".py";
  {
    std::ofstream script(script_path);
    script << kPeer;
    ASSERT_TRUE(script.good()) << "cannot write " << script_path;
  }
  BackgroundCommand peer("exec /usr/bin/python3 " + script_path);

  // The peer sends only after its bus is bound, so once its frame is here ours reaches it.
  const auto from_python = socket.receive(kPythonLimit);
  ASSERT_TRUE(from_python.has_value()) << peer.finish().output;
  EXPECT_EQ(from_python->frame.can_id, CAN_EFF_FLAG | 0x18FF50E5u);
  EXPECT_EQ(std::vector<std::uint8_t>(from_python->frame.data, from_python->frame.data + 3),
            (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(from_python->frame.len, 3);

  socket.send(classic_frame(0x321, {0xAA, 0xBB}));
  const CommandResult result = peer.finish();
  EXPECT_EQ(result.exit_status, 0) << result.output;
  EXPECT_EQ(result.output, "321 0 0 aabb\n");
  std::remove(script_path.c_str());
}

}  // namespace
}  // namespace wavebench::vcan_smoke
