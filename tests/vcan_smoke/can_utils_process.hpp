// Running can-utils (candump, cansend) from a test, and the bits of their text formats the test
// compares against.
#pragma once

#include <linux/can.h>

#include <cstdio>
#include <string>

namespace wavebench::vcan_smoke {

struct CommandResult {
  int exit_status = -1;  // the command's exit code; -1 when it did not exit normally
  std::string output;    // stdout and stderr
};

// Runs `command` through /bin/sh and waits for it.
CommandResult run_command(const std::string& command);

// True when `program` is found on PATH.
bool program_on_path(const std::string& program);

// A command started in the background whose output is collected when it ends. Used for candump,
// which must be listening before the test sends.
class BackgroundCommand {
 public:
  explicit BackgroundCommand(const std::string& command);
  ~BackgroundCommand();
  BackgroundCommand(const BackgroundCommand&) = delete;
  BackgroundCommand& operator=(const BackgroundCommand&) = delete;

  // Reads the output to its end and waits for the command to exit.
  CommandResult finish();

 private:
  FILE* pipe_ = nullptr;
};

// How many CAN receivers (sockets' filters) are registered on `ifname`, summed over
// /proc/net/can/rcvlist_*. A new candump is listening once this count has grown.
int registered_receivers(const std::string& ifname);

// A frame in candump's log format ("-L"): "<ifname> <id>#<data>" for classic frames,
// "<id>#R" for remote frames, "<id>##<flags><data>" for CAN FD; ids as 3 (SFF) or 8 (EFF)
// upper-case hex digits, data as upper-case hex without separators. The leading timestamp
// "(sec.usec) " is not part of it.
std::string candump_log_text(const std::string& ifname, const canfd_frame& frame, bool is_fd);

}  // namespace wavebench::vcan_smoke
