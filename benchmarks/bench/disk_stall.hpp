#pragma once
// A slow disk for the sample log, injected from outside the production code: write(2) and
// fdatasync(2) are interposed in the benchmark's executable (disk_stall.cpp), and once per
// period the first of them on the armed file sleeps `stall` before doing its work, starting
// with the first one after arming.

#include <chrono>
#include <cstdint>
#include <filesystem>

namespace wavebench::benchmarks {

class DiskStall {
 public:
  // Stalls the file at `path` (it must exist) until disarm() or destruction.
  DiskStall(const std::filesystem::path& path, std::chrono::milliseconds stall,
            std::chrono::milliseconds period);
  ~DiskStall();
  DiskStall(const DiskStall&) = delete;
  DiskStall& operator=(const DiskStall&) = delete;

  void disarm() noexcept;
  static std::uint64_t stalls_injected() noexcept;
};

}  // namespace wavebench::benchmarks
