#include "wavebench/storage/sample_log.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include "byte_order.hpp"

namespace wavebench::storage {

namespace {

constexpr char kMagic[8] = {'W', 'B', 'S', 'A', 'M', 'P', 'L', '1'};
using detail::fnv1a32;
using detail::get_f64;
using detail::get_u32;
using detail::get_u64;
using detail::put_f64;
using detail::put_u32;
using detail::put_u64;

std::int64_t realtime_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

SyncSample decode_record(const unsigned char* r) {
  SyncSample s;
  s.index = get_u64(r + 0);
  s.sync_counter = get_u32(r + 8);
  s.flags = get_u32(r + 12);
  s.receive_time_ns = static_cast<std::int64_t>(get_u64(r + 16));
  s.theta_in_rad = get_f64(r + 24);
  s.theta_out_rad = get_f64(r + 32);
  s.input_speed_rad_s = get_f64(r + 40);
  s.torque_nm = get_f64(r + 48);
  s.brake_current_a = get_f64(r + 56);
  s.brake_torque_nm = get_f64(r + 64);
  s.missed_before = get_u32(r + 72);
  return s;
}

// Checks and decodes the 64 header bytes; `size` is how many bytes the file has.
SampleLogHeader decode_header(const unsigned char* h, std::size_t size,
                              const std::filesystem::path& path) {
  if (size < kSampleLogHeaderSize) {
    throw std::runtime_error("sample log " + path.string() + ": header is " + std::to_string(size) +
                             " bytes; expected " + std::to_string(kSampleLogHeaderSize));
  }
  if (std::memcmp(h, kMagic, sizeof kMagic) != 0) {
    throw std::runtime_error("sample log " + path.string() + ": magic is not WBSAMPL1");
  }
  if (get_u32(h + 60) != fnv1a32(h, 60)) {
    throw std::runtime_error("sample log " + path.string() + ": header checksum mismatch");
  }
  SampleLogHeader header;
  header.version = get_u32(h + 8);
  const std::uint32_t header_size = get_u32(h + 12);
  const std::uint32_t record_size = get_u32(h + 16);
  if (header.version != kSampleLogVersion || header_size != kSampleLogHeaderSize ||
      record_size != kSampleLogRecordSize) {
    throw std::runtime_error("sample log " + path.string() + ": version " +
                             std::to_string(header.version) + ", record size " +
                             std::to_string(record_size) + "; expected version " +
                             std::to_string(kSampleLogVersion) + ", record size " +
                             std::to_string(kSampleLogRecordSize));
  }
  header.counter_range.first = get_u32(h + 20);
  header.counter_range.last = get_u32(h + 24);
  header.created_ns = static_cast<std::int64_t>(get_u64(h + 32));
  return header;
}

bool record_intact(const unsigned char* r) {
  return get_u32(r + 92) == fnv1a32(r, 92);
}

// Reads exactly `size` bytes at `offset` (the file was measured first, so a short read means
// it shrank under us).
void read_at(int fd, unsigned char* data, std::size_t size, std::uint64_t offset,
             const std::filesystem::path& path) {
  while (size > 0) {
    const ssize_t n = ::pread(fd, data, size, static_cast<off_t>(offset));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::generic_category(), "sample log: read " + path.string());
    }
    if (n == 0) {
      throw std::runtime_error("sample log " + path.string() + ": file shrank while reading");
    }
    data += n;
    size -= static_cast<std::size_t>(n);
    offset += static_cast<std::uint64_t>(n);
  }
}

class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::vector<unsigned char> encode_sample_log_header(const SampleLogHeader& header) {
  std::vector<unsigned char> h(kSampleLogHeaderSize, 0);
  std::memcpy(h.data(), kMagic, sizeof kMagic);
  put_u32(&h[8], header.version);
  put_u32(&h[12], static_cast<std::uint32_t>(kSampleLogHeaderSize));
  put_u32(&h[16], static_cast<std::uint32_t>(kSampleLogRecordSize));
  put_u32(&h[20], header.counter_range.first);
  put_u32(&h[24], header.counter_range.last);
  put_u64(&h[32], static_cast<std::uint64_t>(header.created_ns));
  put_u32(&h[60], fnv1a32(h.data(), 60));
  return h;
}

std::vector<unsigned char> encode_sample_record(const SyncSample& s) {
  std::vector<unsigned char> r(kSampleLogRecordSize, 0);
  put_u64(&r[0], s.index);
  put_u32(&r[8], s.sync_counter);
  put_u32(&r[12], s.flags);
  put_u64(&r[16], static_cast<std::uint64_t>(s.receive_time_ns));
  put_f64(&r[24], s.theta_in_rad);
  put_f64(&r[32], s.theta_out_rad);
  put_f64(&r[40], s.input_speed_rad_s);
  put_f64(&r[48], s.torque_nm);
  put_f64(&r[56], s.brake_current_a);
  put_f64(&r[64], s.brake_torque_nm);
  put_u32(&r[72], s.missed_before);
  put_u32(&r[92], fnv1a32(r.data(), 92));
  return r;
}

SampleLogWriter::SampleLogWriter(const std::filesystem::path& path, SampleLogWriterOptions options)
    : path_(path), options_(options), gaps_(options.counter_range) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::system_error(errno, std::generic_category(),
                            "sample log: cannot create " + path.string());
  }
  SampleLogHeader header;
  header.counter_range = options.counter_range;
  header.created_ns = realtime_ns();
  const auto bytes = encode_sample_log_header(header);
  try {
    write_all(bytes.data(), bytes.size());
    if (::fdatasync(fd_) != 0) {
      const int e = errno;
      fail(e, "sample log: fdatasync " + path.string());
    }
  } catch (...) {
    ::close(fd_);  // the destructor does not run for a constructor that throws
    fd_ = -1;
    throw;
  }
  buffer_.reserve(options.flush_every_records * kSampleLogRecordSize);
  last_flush_ = std::chrono::steady_clock::now();
}

SampleLogWriter::~SampleLogWriter() {
  try {
    close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor cannot report; close() can
  }
}

SyncSample SampleLogWriter::append(SyncSample sample) {
  if (fd_ < 0) throw std::logic_error("sample log: append after close of " + path_.string());
  if (write_error_ != 0) fail(write_error_, write_error_what_);
  sample.index = next_index_++;
  sample.flags &= ~(kGapBefore | kCounterAnomaly);
  gaps_.observe(sample);
  const auto record = encode_sample_record(sample);
  buffer_.insert(buffer_.end(), record.begin(), record.end());
  const std::size_t buffered = buffer_.size() / kSampleLogRecordSize;
  if (buffered >= options_.flush_every_records ||
      std::chrono::steady_clock::now() - last_flush_ >= options_.flush_interval) {
    flush();
  }
  if (options_.checkpoint_every_records > 0 &&
      flushed_ - synced_ >= options_.checkpoint_every_records) {
    checkpoint();
  }
  return sample;
}

void SampleLogWriter::write_all(const unsigned char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0) {
      const int e = errno;
      if (e == EINTR) continue;
      fail(e, "sample log: write " + path_.string());
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void SampleLogWriter::fail(int error, const std::string& what) {
  if (write_error_ == 0) {
    write_error_ = error;
    write_error_what_ = what;
  }
  throw std::system_error(error, std::generic_category(), what);
}

void SampleLogWriter::flush() {
  if (fd_ < 0) return;
  if (write_error_ != 0) fail(write_error_, write_error_what_);
  if (!buffer_.empty()) {
    write_all(buffer_.data(), buffer_.size());
    flushed_ += buffer_.size() / kSampleLogRecordSize;
    buffer_.clear();
  }
  last_flush_ = std::chrono::steady_clock::now();
}

void SampleLogWriter::flush_if_due() {
  if (std::chrono::steady_clock::now() - last_flush_ >= options_.flush_interval) flush();
}

void SampleLogWriter::checkpoint() {
  flush();
  if (fd_ < 0) return;
  if (::fdatasync(fd_) != 0) {
    const int e = errno;
    fail(e, "sample log: fdatasync " + path_.string());
  }
  synced_ = flushed_;
}

void SampleLogWriter::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  if (write_error_ == 0) {
    try {
      checkpoint();
    } catch (...) {
      fd_ = -1;
      ::close(fd);
      throw;
    }
  }
  fd_ = -1;
  ::close(fd);
}

SampleLogContents read_sample_log(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("sample log: cannot open " + path.string());
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  SampleLogContents out;
  out.header = decode_header(bytes.data(), bytes.size(), path);

  SyncGapCounter recount(out.header.counter_range);
  std::size_t offset = kSampleLogHeaderSize;
  while (offset + kSampleLogRecordSize <= bytes.size()) {
    const unsigned char* r = &bytes[offset];
    if (!record_intact(r)) {
      out.corrupt_record = true;
      out.corrupt_at_index = out.samples.size();
      return out;
    }
    SyncSample s = decode_record(r);
    SyncSample check = s;
    recount.observe(check);
    out.samples.push_back(s);
    offset += kSampleLogRecordSize;
  }
  out.torn_tail_bytes = bytes.size() - offset;
  out.gaps = recount.totals();
  return out;
}

SampleLogPage read_sample_log_page(const std::filesystem::path& path, std::uint64_t from,
                                   std::size_t count) {
  if (count > kMaxSampleLogPageRecords) {
    throw std::invalid_argument("sample log page: count " + std::to_string(count) +
                                "; expected at most " + std::to_string(kMaxSampleLogPageRecords) +
                                " records");
  }
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) {
    throw std::system_error(errno, std::generic_category(),
                            "sample log: cannot open " + path.string());
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) {
    throw std::system_error(errno, std::generic_category(), "sample log: stat " + path.string());
  }
  const auto size = static_cast<std::uint64_t>(st.st_size);
  unsigned char h[kSampleLogHeaderSize];
  const std::size_t header_bytes =
      static_cast<std::size_t>(std::min<std::uint64_t>(size, kSampleLogHeaderSize));
  read_at(fd.get(), h, header_bytes, 0, path);

  SampleLogPage page;
  page.header = decode_header(h, header_bytes, path);
  page.from = from;
  page.total_records = (size - kSampleLogHeaderSize) / kSampleLogRecordSize;
  page.torn_tail_bytes =
      static_cast<std::size_t>((size - kSampleLogHeaderSize) % kSampleLogRecordSize);
  if (from >= page.total_records || count == 0) return page;
  const auto n =
      static_cast<std::size_t>(std::min<std::uint64_t>(count, page.total_records - from));
  std::vector<unsigned char> bytes(n * kSampleLogRecordSize);
  read_at(fd.get(), bytes.data(), bytes.size(), kSampleLogHeaderSize + from * kSampleLogRecordSize,
          path);
  page.samples.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* r = &bytes[i * kSampleLogRecordSize];
    if (!record_intact(r)) {
      page.corrupt_record = true;
      page.corrupt_at_index = from + i;
      break;
    }
    page.samples.push_back(decode_record(r));
  }
  return page;
}

}  // namespace wavebench::storage
