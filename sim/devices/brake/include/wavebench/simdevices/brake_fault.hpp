#pragma once
// Faults the simulated brake controller can be told to commit, for tests of the client.

#include <chrono>

namespace wavebench::simdevices {

enum class BrakeFaultKind {
  none,
  delayed_reply,       // answer correctly, `delay` late
  exception_response,  // answer with Modbus exception `exception_code`
  dropped_connection,  // close the TCP connection instead of answering (RTU: stay silent)
  wrong_unit_id,       // answer correctly but from unit id `wrong_unit_id`
  garbage_bytes,       // answer with bytes that are no valid frame
};

struct BrakeFault {
  BrakeFaultKind kind = BrakeFaultKind::none;
  std::chrono::milliseconds delay{0};
  int exception_code = 6;  // server device busy
  int wrong_unit_id = -1;  // -1: the configured unit id + 1
  int requests = -1;       // how many requests it affects; -1 until cleared
};

}  // namespace wavebench::simdevices
