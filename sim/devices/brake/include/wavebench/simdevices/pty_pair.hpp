#pragma once
// A pseudo-terminal pair standing in for a serial line: the simulated controller keeps the
// master side, a client opens `slave_path()` as its serial device.

#include <string>

namespace wavebench::simdevices {

class PtyPair {
 public:
  PtyPair();  // throws std::system_error
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  int master_fd() const noexcept { return master_; }
  const std::string& slave_path() const noexcept { return slave_path_; }
  // Hands the master fd over (e.g. to a BrakeServer, which then closes it).
  int release_master() noexcept;

 private:
  int master_ = -1;
  int slave_ = -1;  // held open so the master never sees a hang-up between clients
  std::string slave_path_;
};

}  // namespace wavebench::simdevices
