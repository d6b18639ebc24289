#include "disk_stall.hpp"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <thread>

namespace wavebench::benchmarks {
namespace {

std::atomic<bool> armed{false};
std::atomic<dev_t> armed_device{0};
std::atomic<ino_t> armed_inode{0};
std::atomic<std::int64_t> stall_ns{0};
std::atomic<std::int64_t> period_ns{0};
std::atomic<std::int64_t> next_stall_ns{0};
std::atomic<std::uint64_t> injected{0};

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Called before every write(2)/fdatasync(2) of the process: cheap unless a stall is due.
void maybe_stall(int fd) noexcept {
  if (!armed.load(std::memory_order_acquire)) return;
  std::int64_t due = next_stall_ns.load(std::memory_order_relaxed);
  const std::int64_t now = steady_ns();
  if (now < due) return;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_ino != armed_inode.load() || st.st_dev != armed_device.load())
    return;
  if (!next_stall_ns.compare_exchange_strong(due, now + period_ns.load())) return;
  injected.fetch_add(1);
  std::this_thread::sleep_for(std::chrono::nanoseconds(stall_ns.load()));
}

template <class F>
F real(const char* name) {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): dlsym's contract
  return reinterpret_cast<F>(::dlsym(RTLD_NEXT, name));
}

}  // namespace

DiskStall::DiskStall(const std::filesystem::path& path, std::chrono::milliseconds stall,
                     std::chrono::milliseconds period) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw std::runtime_error("disk stall: cannot stat " + path.string());
  }
  armed_device = st.st_dev;
  armed_inode = st.st_ino;
  stall_ns = std::chrono::nanoseconds(stall).count();
  period_ns = std::chrono::nanoseconds(period).count();
  // The first write after arming stalls: a short round gets its stall a second like a long one.
  next_stall_ns = steady_ns();
  armed.store(true, std::memory_order_release);
}

DiskStall::~DiskStall() {
  disarm();
}

void DiskStall::disarm() noexcept {
  armed.store(false, std::memory_order_release);
}

std::uint64_t DiskStall::stalls_injected() noexcept {
  return injected.load();
}

}  // namespace wavebench::benchmarks

// The interposed calls: the executable's definitions come before libc's for every caller in
// the process, including the sample log writer in libwavebench_storage.a.
extern "C" ssize_t write(int fd, const void* data, size_t size) {
  static const auto next =
      wavebench::benchmarks::real<ssize_t (*)(int, const void*, size_t)>("write");
  wavebench::benchmarks::maybe_stall(fd);
  return next(fd, data, size);
}

extern "C" int fdatasync(int fd) {
  static const auto next = wavebench::benchmarks::real<int (*)(int)>("fdatasync");
  wavebench::benchmarks::maybe_stall(fd);
  return next(fd);
}
