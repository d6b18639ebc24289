#pragma once
// POST /api/manual/{action} (the console's manual panel, manual_session.hpp):
//   jog    {"speed_rpm": ±n}        run the input at n rpm; repeat every ~100 ms while held
//   stop   {}                       end the jog (a go-to in progress: trips the bench)
//   goto   {"angle_deg": a, "speed_rpm": n}   turn the output the shorter way to a° in its turn
//   brake  {"torque_nm": t}         brake torque (0: off)
//   servo  {"on": true|false}       hold the input / inactive (drive disabled, brake off)
//   alive  {}                       keep-alive while the panel holds something
// Authorisation is the caller's (DaemonApi::refuse_change). A value out of its bound is 400
// naming the key, the value and the bound, before anything moves; a state that forbids the
// action (a run, a fault) is 409.

#include <string>

#include "wavebench/daemon/bench_thread.hpp"
#include "wavebench/daemon/daemon_api.hpp"

namespace wavebench::daemon {

ApiResponse manual_request(BenchThread& bench, const std::string& action, const std::string& body);

// The panel's part of /api/status: its state and its bounds.
nlohmann::json manual_json(const ManualState& state);

}  // namespace wavebench::daemon
