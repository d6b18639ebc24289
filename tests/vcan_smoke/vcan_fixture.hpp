// Tests in this directory need a real SocketCAN vcan0 (the qemu VM of scripts/vcan-vm/ creates
// it); elsewhere they skip.
#pragma once

#include <gtest/gtest.h>

#include <chrono>

#include "can_raw_socket.hpp"

namespace wavebench::vcan_smoke {

inline constexpr const char* kVcan = "vcan0";
// Only a guard against hanging: every receive waits for a frame that was already sent.
inline constexpr std::chrono::milliseconds kReceiveLimit{20000};

class VcanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!can_interface_available(kVcan)) {
      GTEST_SKIP() << kVcan << " is absent (no CAN support or no vcan0 on this kernel); "
                   << "run scripts/vcan-vm/run-vcan-tests.sh BUILD_DIR";
    }
  }
};

}  // namespace wavebench::vcan_smoke
