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

constexpr std::size_t kChannelEntryBytes = 48;  // 32-byte name + 16-byte unit

// Versions 1 and 2 hold six core values at offsets 24..71, then missed_before at 72: a seventh
// core channel is a new record layout, so a new version (keep reading these).
static_assert(kCoreChannels.size() == 6 && kCoreChannels.back().record_offset + 8 == 72,
              "a core channel changes the sample log record: bump kSampleLogVersion");

SyncSample decode_record(const unsigned char* r, std::size_t extra_channels) {
  SyncSample s;
  s.index = get_u64(r + 0);
  s.sync_counter = get_u32(r + 8);
  s.flags = get_u32(r + 12);
  s.receive_time_ns = static_cast<std::int64_t>(get_u64(r + 16));
  for (const auto& c : kCoreChannels) s.*c.value = get_f64(r + c.record_offset);
  s.missed_before = get_u32(r + 72);
  if (extra_channels > 0) {
    s.extra_valid = get_u32(r + 76) & ((1U << extra_channels) - 1U);
    for (std::size_t i = 0; i < extra_channels; ++i) s.extra[i] = get_f64(r + 80 + 8 * i);
  }
  return s;
}

std::string padded_text(const unsigned char* p, std::size_t size) {
  std::size_t n = 0;
  while (n < size && p[n] != 0) ++n;
  return std::string(reinterpret_cast<const char*>(p), n);
}

// Checks and decodes the 64-byte prologue; `size` is how many bytes the file has. Sets
// header_size and record_size; a version 2 header's channel table is read by decode_table.
SampleLogHeader decode_prologue(const unsigned char* h, std::size_t size,
                                const std::filesystem::path& path) {
  if (size < kSampleLogPrologueSize) {
    throw std::runtime_error("sample log " + path.string() + ": header is " + std::to_string(size) +
                             " bytes; expected at least " + std::to_string(kSampleLogPrologueSize));
  }
  if (std::memcmp(h, kMagic, sizeof kMagic) != 0) {
    throw std::runtime_error("sample log " + path.string() + ": magic is not WBSAMPL1");
  }
  if (get_u32(h + 60) != fnv1a32(h, 60)) {
    throw std::runtime_error("sample log " + path.string() + ": header checksum mismatch");
  }
  SampleLogHeader header;
  header.version = get_u32(h + 8);
  header.header_size = get_u32(h + 12);
  header.record_size = get_u32(h + 16);
  const bool v1 = header.version == 1 && header.header_size == kSampleLogPrologueSize &&
                  header.record_size == kSampleLogRecordSize;
  const bool v2 = header.version == 2 && header.header_size >= sample_log_header_size(0) &&
                  header.header_size <= sample_log_header_size(kMaxExtraChannels) &&
                  header.record_size >= sample_log_record_size(0) &&
                  header.record_size <= sample_log_record_size(kMaxExtraChannels);
  if (!v1 && !v2) {
    throw std::runtime_error("sample log " + path.string() + ": version " +
                             std::to_string(header.version) + ", header size " +
                             std::to_string(header.header_size) + ", record size " +
                             std::to_string(header.record_size) +
                             "; expected version 1 (64, 96) or 2 (with its channel table)");
  }
  header.counter_range.first = get_u32(h + 20);
  header.counter_range.last = get_u32(h + 24);
  header.created_ns = static_cast<std::int64_t>(get_u64(h + 32));
  return header;
}

// The channel table that follows a version 2 prologue: `t` holds header_size - 64 bytes.
void decode_table(const unsigned char* t, SampleLogHeader& header,
                  const std::filesystem::path& path) {
  const std::size_t table_bytes = header.header_size - kSampleLogPrologueSize;
  const std::uint32_t count = get_u32(t);
  const auto core = core_channels();
  if (count < core.size() || count - core.size() > kMaxExtraChannels ||
      sample_log_header_size(count - core.size()) != header.header_size ||
      sample_log_record_size(count - core.size()) != header.record_size) {
    throw std::runtime_error("sample log " + path.string() + ": channel table of " +
                             std::to_string(count) + " channels does not match header size " +
                             std::to_string(header.header_size) + " and record size " +
                             std::to_string(header.record_size));
  }
  const std::size_t checked = 8 + count * kChannelEntryBytes;
  if (checked + 8 != table_bytes || get_u32(t + checked) != fnv1a32(t, checked)) {
    throw std::runtime_error("sample log " + path.string() + ": channel table checksum mismatch");
  }
  header.extra_channels.clear();
  for (std::uint32_t i = 0; i < count; ++i) {
    const unsigned char* e = t + 8 + i * kChannelEntryBytes;
    ChannelInfo c{padded_text(e, 32), padded_text(e + 32, 16)};
    if (i < core.size()) {
      if (c != core[i])
        throw std::runtime_error("sample log " + path.string() + ": channel " + std::to_string(i) +
                                 " is '" + c.name + "' [" + c.unit + "]; expected '" +
                                 core[i].name + "' [" + core[i].unit + "]");
    } else {
      header.extra_channels.push_back(std::move(c));
    }
  }
  try {
    check_extra_channels(header.extra_channels);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error("sample log " + path.string() + ": " + e.what());
  }
}

std::size_t extra_count(const SampleLogHeader& header) {
  return header.extra_channels.size();
}

bool record_intact(const unsigned char* r, std::size_t record_size) {
  return get_u32(r + record_size - 4) == fnv1a32(r, record_size - 4);
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

std::size_t sample_log_header_size(std::size_t extra_channels) {
  return kSampleLogPrologueSize + 8 +
         (core_channels().size() + extra_channels) * kChannelEntryBytes + 8;
}

std::size_t sample_log_record_size(std::size_t extra_channels) {
  return kSampleLogRecordSize + 8 * extra_channels;
}

std::vector<unsigned char> encode_sample_log_header(const SampleLogHeader& header) {
  const bool v1 = header.version == 1;
  if (v1 && !header.extra_channels.empty())
    throw std::invalid_argument("sample log version 1 has no extra channels");
  check_extra_channels(header.extra_channels);
  const std::size_t extras = header.extra_channels.size();
  const std::size_t header_size = v1 ? kSampleLogPrologueSize : sample_log_header_size(extras);
  std::vector<unsigned char> h(header_size, 0);
  std::memcpy(h.data(), kMagic, sizeof kMagic);
  put_u32(&h[8], v1 ? 1 : kSampleLogVersion);
  put_u32(&h[12], static_cast<std::uint32_t>(header_size));
  put_u32(&h[16],
          static_cast<std::uint32_t>(v1 ? kSampleLogRecordSize : sample_log_record_size(extras)));
  put_u32(&h[20], header.counter_range.first);
  put_u32(&h[24], header.counter_range.last);
  put_u64(&h[32], static_cast<std::uint64_t>(header.created_ns));
  put_u32(&h[60], fnv1a32(h.data(), 60));
  if (v1) return h;
  unsigned char* t = &h[kSampleLogPrologueSize];
  std::vector<ChannelInfo> all(core_channels().begin(), core_channels().end());
  all.insert(all.end(), header.extra_channels.begin(), header.extra_channels.end());
  put_u32(t, static_cast<std::uint32_t>(all.size()));
  for (std::size_t i = 0; i < all.size(); ++i) {
    unsigned char* e = t + 8 + i * kChannelEntryBytes;
    std::memcpy(e, all[i].name.data(), std::min<std::size_t>(all[i].name.size(), 31));
    std::memcpy(e + 32, all[i].unit.data(), std::min<std::size_t>(all[i].unit.size(), 15));
  }
  const std::size_t checked = 8 + all.size() * kChannelEntryBytes;
  put_u32(t + checked, fnv1a32(t, checked));
  return h;
}

std::vector<unsigned char> encode_sample_record(const SyncSample& s, std::size_t extra_channels) {
  if (extra_channels > kMaxExtraChannels)
    throw std::invalid_argument("sample record: " + std::to_string(extra_channels) +
                                " extra channels; expected at most " +
                                std::to_string(kMaxExtraChannels));
  const std::size_t size = sample_log_record_size(extra_channels);
  std::vector<unsigned char> r(size, 0);
  put_u64(&r[0], s.index);
  put_u32(&r[8], s.sync_counter);
  put_u32(&r[12], s.flags);
  put_u64(&r[16], static_cast<std::uint64_t>(s.receive_time_ns));
  for (const auto& c : kCoreChannels) put_f64(&r[c.record_offset], s.*c.value);
  put_u32(&r[72], s.missed_before);
  if (extra_channels > 0) {
    put_u32(&r[76], s.extra_valid & ((1U << extra_channels) - 1U));
    for (std::size_t i = 0; i < extra_channels; ++i) put_f64(&r[80 + 8 * i], s.extra[i]);
  }
  put_u32(&r[size - 4], fnv1a32(r.data(), size - 4));
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
  header.extra_channels = options.extra_channels;
  std::vector<unsigned char> bytes;
  try {
    bytes = encode_sample_log_header(header);
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
  record_size_ = sample_log_record_size(options.extra_channels.size());
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
  buffer_.reserve(options.flush_every_records * record_size_);
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
  const auto record = encode_sample_record(sample, options_.extra_channels.size());
  buffer_.insert(buffer_.end(), record.begin(), record.end());
  const std::size_t buffered = buffer_.size() / record_size_;
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
    flushed_ += buffer_.size() / record_size_;
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
  out.header = decode_prologue(bytes.data(), bytes.size(), path);
  if (out.header.version >= 2) {
    if (bytes.size() < out.header.header_size)
      throw std::runtime_error("sample log " + path.string() + ": header is " +
                               std::to_string(bytes.size()) + " bytes; expected " +
                               std::to_string(out.header.header_size));
    decode_table(&bytes[kSampleLogPrologueSize], out.header, path);
  }
  const std::size_t record_size = out.header.record_size;
  const std::size_t extras = extra_count(out.header);

  SyncGapCounter recount(out.header.counter_range);
  std::size_t offset = out.header.header_size;
  while (offset + record_size <= bytes.size()) {
    const unsigned char* r = &bytes[offset];
    if (!record_intact(r, record_size)) {
      out.corrupt_record = true;
      out.corrupt_at_index = out.samples.size();
      return out;
    }
    SyncSample s = decode_record(r, extras);
    SyncSample check = s;
    recount.observe(check);
    out.samples.push_back(s);
    offset += record_size;
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
  unsigned char h[kSampleLogPrologueSize];
  const std::size_t prologue_bytes =
      static_cast<std::size_t>(std::min<std::uint64_t>(size, kSampleLogPrologueSize));
  read_at(fd.get(), h, prologue_bytes, 0, path);

  SampleLogPage page;
  page.header = decode_prologue(h, prologue_bytes, path);
  const std::size_t header_size = page.header.header_size;
  if (size < header_size)
    throw std::runtime_error("sample log " + path.string() + ": header is " + std::to_string(size) +
                             " bytes; expected " + std::to_string(header_size));
  if (page.header.version >= 2) {
    std::vector<unsigned char> table(header_size - kSampleLogPrologueSize);
    read_at(fd.get(), table.data(), table.size(), kSampleLogPrologueSize, path);
    decode_table(table.data(), page.header, path);
  }
  const std::size_t record_size = page.header.record_size;
  const std::size_t extras = extra_count(page.header);
  page.from = from;
  page.total_records = (size - header_size) / record_size;
  page.torn_tail_bytes = static_cast<std::size_t>((size - header_size) % record_size);
  if (from >= page.total_records || count == 0) return page;
  const auto n =
      static_cast<std::size_t>(std::min<std::uint64_t>(count, page.total_records - from));
  std::vector<unsigned char> bytes(n * record_size);
  read_at(fd.get(), bytes.data(), bytes.size(), header_size + from * record_size, path);
  page.samples.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* r = &bytes[i * record_size];
    if (!record_intact(r, record_size)) {
      page.corrupt_record = true;
      page.corrupt_at_index = from + i;
      break;
    }
    page.samples.push_back(decode_record(r, extras));
  }
  return page;
}

}  // namespace wavebench::storage
