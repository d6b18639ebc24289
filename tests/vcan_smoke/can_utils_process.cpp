#include "can_utils_process.hpp"

#include <sys/wait.h>

#include <array>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace wavebench::vcan_smoke {
namespace {

int exit_code(int wait_status) {
  return (wait_status != -1 && WIFEXITED(wait_status)) ? WEXITSTATUS(wait_status) : -1;
}

std::string read_all(FILE* pipe) {
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  return out;
}

}  // namespace

CommandResult run_command(const std::string& command) {
  BackgroundCommand cmd(command);
  return cmd.finish();
}

bool program_on_path(const std::string& program) {
  return run_command("command -v " + program + " >/dev/null").exit_status == 0;
}

BackgroundCommand::BackgroundCommand(const std::string& command) {
  pipe_ = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe_ == nullptr) throw std::runtime_error("popen failed for: " + command);
}

BackgroundCommand::~BackgroundCommand() {
  if (pipe_ != nullptr) ::pclose(pipe_);
}

CommandResult BackgroundCommand::finish() {
  if (pipe_ == nullptr) throw std::logic_error("BackgroundCommand::finish called twice");
  CommandResult result;
  result.output = read_all(pipe_);
  result.exit_status = exit_code(::pclose(pipe_));
  pipe_ = nullptr;
  return result;
}

int registered_receivers(const std::string& ifname) {
  int count = 0;
  for (const char* list : {"all", "fil", "inv", "sff", "eff", "err"}) {
    std::ifstream in(std::string("/proc/net/can/rcvlist_") + list);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string first;
      words >> first;
      if (first == ifname) ++count;
    }
  }
  return count;
}

std::string candump_log_text(const std::string& ifname, const canfd_frame& frame, bool is_fd) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string text = ifname + ' ';
  char id[16];
  if (frame.can_id & CAN_EFF_FLAG) {
    std::snprintf(id, sizeof id, "%08X", frame.can_id & CAN_EFF_MASK);
  } else {
    std::snprintf(id, sizeof id, "%03X", frame.can_id & CAN_SFF_MASK);
  }
  text += id;
  text += '#';
  if (!is_fd && (frame.can_id & CAN_RTR_FLAG)) {
    text += 'R';
    if (frame.len > 0) text += kHex[frame.len & 0xF];
    return text;
  }
  if (is_fd) {
    text += '#';
    text += kHex[frame.flags & 0xF];
  }
  for (int i = 0; i < frame.len; ++i) {
    text += kHex[frame.data[i] >> 4];
    text += kHex[frame.data[i] & 0xF];
  }
  return text;
}

}  // namespace wavebench::vcan_smoke
