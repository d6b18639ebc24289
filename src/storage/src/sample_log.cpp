#include "wavebench/storage/sample_log.hpp"

#include <fcntl.h>
#include <unistd.h>

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
  write_all(bytes.data(), bytes.size());
  if (::fdatasync(fd_) != 0) {
    throw std::system_error(errno, std::generic_category(),
                            "sample log: fdatasync " + path.string());
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
      if (errno == EINTR) continue;
      throw std::system_error(errno, std::generic_category(),
                              "sample log: write " + path_.string());
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void SampleLogWriter::flush() {
  if (fd_ < 0) return;
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
    throw std::system_error(errno, std::generic_category(),
                            "sample log: fdatasync " + path_.string());
  }
  synced_ = flushed_;
}

void SampleLogWriter::close() {
  if (fd_ < 0) return;
  checkpoint();
  ::close(fd_);
  fd_ = -1;
}

SampleLogContents read_sample_log(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("sample log: cannot open " + path.string());
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.size() < kSampleLogHeaderSize) {
    throw std::runtime_error("sample log " + path.string() + ": header is " +
                             std::to_string(bytes.size()) + " bytes; expected " +
                             std::to_string(kSampleLogHeaderSize));
  }
  if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    throw std::runtime_error("sample log " + path.string() + ": magic is not WBSAMPL1");
  }
  if (get_u32(&bytes[60]) != fnv1a32(bytes.data(), 60)) {
    throw std::runtime_error("sample log " + path.string() + ": header checksum mismatch");
  }
  SampleLogContents out;
  out.header.version = get_u32(&bytes[8]);
  const std::uint32_t header_size = get_u32(&bytes[12]);
  const std::uint32_t record_size = get_u32(&bytes[16]);
  if (out.header.version != kSampleLogVersion || header_size != kSampleLogHeaderSize ||
      record_size != kSampleLogRecordSize) {
    throw std::runtime_error("sample log " + path.string() + ": version " +
                             std::to_string(out.header.version) + ", record size " +
                             std::to_string(record_size) + "; expected version " +
                             std::to_string(kSampleLogVersion) + ", record size " +
                             std::to_string(kSampleLogRecordSize));
  }
  out.header.counter_range.first = get_u32(&bytes[20]);
  out.header.counter_range.last = get_u32(&bytes[24]);
  out.header.created_ns = static_cast<std::int64_t>(get_u64(&bytes[32]));

  SyncGapCounter recount(out.header.counter_range);
  std::size_t offset = kSampleLogHeaderSize;
  while (offset + kSampleLogRecordSize <= bytes.size()) {
    const unsigned char* r = &bytes[offset];
    if (get_u32(r + 92) != fnv1a32(r, 92)) {
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

}  // namespace wavebench::storage
