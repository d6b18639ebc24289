#pragma once
// Append-only binary log of SyncSamples, one file per run, written as acquired.
//
// Layout (little-endian; docs/sample-log.md is the written schema). Version 2 (written):
//   header: the 64-byte prologue of version 1 (version 2, its header_size and record_size),
//           then the channel table: u32 channel_count | u32 0 | channel_count x (32-byte name,
//           16-byte unit, NUL-padded) | u32 FNV-1a of the table | u32 0. The first six
//           channels are the core ones (core_channels()); the rest are the bench's extra ones.
//   record: as version 1 up to missed_before (76 bytes) | u32 extra_valid | one f64 per extra
//           channel | 12 bytes zero | u32 FNV-1a of the bytes before it (96 + 8 x extras bytes)
// Version 1 (still read): a 64-byte header, then fixed-size 96-byte records:
//   header: magic "WBSAMPL1" | u32 version | u32 header_size | u32 record_size |
//           u32 counter_first | u32 counter_last | u32 pad | i64 created_ns | 24 bytes zero |
//           u32 FNV-1a of the bytes before it
//   record: u64 index | u32 sync_counter | u32 flags | i64 receive_time_ns | 6 x f64 channels |
//           u32 missed_before | 20 bytes zero | u32 FNV-1a of the bytes before it

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sync_gap_counter.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage {

inline constexpr std::uint32_t kSampleLogVersion = 2;
inline constexpr std::size_t kSampleLogPrologueSize = 64;
inline constexpr std::size_t kSampleLogRecordSize = 96;  // version 1; version 2 without extras

struct SampleLogHeader {
  std::uint32_t version = kSampleLogVersion;
  SyncCounterRange counter_range;
  std::int64_t created_ns = 0;              // CLOCK_REALTIME when the log was created
  std::vector<ChannelInfo> extra_channels;  // named in the header (version 2)
  // Sizes as the file states them (set by the reader; the writer derives them).
  std::size_t header_size = 0;
  std::size_t record_size = 0;
};

std::size_t sample_log_header_size(std::size_t extra_channels);
std::size_t sample_log_record_size(std::size_t extra_channels);

struct SampleLogWriterOptions {
  SyncCounterRange counter_range;
  std::vector<ChannelInfo> extra_channels;        // SyncSample::extra[0..n), checked
  std::size_t flush_every_records = 100;          // write(2) at least this often ...
  std::chrono::milliseconds flush_interval{100};  // ... and at least this often
  std::size_t checkpoint_every_records = 1000;    // fdatasync(2); 0 = only on checkpoint()
};

// Not copyable: owns the file descriptor. Samples go to the OS at every flush, so a killed
// process loses at most what was buffered since the last flush; checkpoints also survive a
// power loss.
class SampleLogWriter {
 public:
  // Creates (truncates) `path`. Throws std::system_error naming the path.
  SampleLogWriter(const std::filesystem::path& path, SampleLogWriterOptions options = {});
  ~SampleLogWriter();
  SampleLogWriter(const SampleLogWriter&) = delete;
  SampleLogWriter& operator=(const SampleLogWriter&) = delete;

  // Counts gaps from the SYNC counter, stamps index/missed_before/flags, buffers the record.
  // Returns the sample as stored.
  SyncSample append(SyncSample sample);
  void flush();
  // For the acquisition's timer: flushes when the interval has passed since the last flush,
  // so a stalled bus does not leave samples buffered.
  void flush_if_due();
  void checkpoint();  // flush + fdatasync
  void close();       // checkpoint and close; the destructor does it too

  std::uint64_t records_appended() const { return next_index_; }
  std::uint64_t records_flushed() const { return flushed_; }
  const SyncGapTotals& gap_totals() const { return gaps_.totals(); }
  const std::filesystem::path& path() const { return path_; }
  // errno of the first failed write or fdatasync, 0 while none failed. After a failure the
  // writer touches the file no more (a failing disk can be slow to fail again): append() and
  // flush() rethrow the first error, close() only closes the descriptor.
  int write_error() const { return write_error_; }

 private:
  void write_all(const unsigned char* data, std::size_t size);
  [[noreturn]] void fail(int error, const std::string& what);

  std::filesystem::path path_;
  SampleLogWriterOptions options_;
  SyncGapCounter gaps_;
  int fd_ = -1;
  std::size_t record_size_ = kSampleLogRecordSize;
  std::vector<unsigned char> buffer_;
  std::uint64_t next_index_ = 0;
  std::uint64_t flushed_ = 0;
  std::uint64_t synced_ = 0;
  std::chrono::steady_clock::time_point last_flush_;
  int write_error_ = 0;
  std::string write_error_what_;
};

struct SampleLogContents {
  SampleLogHeader header;
  std::vector<SyncSample> samples;  // every complete, intact record, in order
  std::size_t torn_tail_bytes = 0;  // bytes of an incomplete last record (ignored)
  bool corrupt_record = false;      // a full-size record failed its checksum; reading stopped
  std::uint64_t corrupt_at_index = 0;
  SyncGapTotals gaps;  // recounted from the records read
};

// Throws std::runtime_error naming the path and what is wrong with the header.
SampleLogContents read_sample_log(const std::filesystem::path& path);

// A page of a log: records [from, from + count) and what the file holds, reading only the
// header and those records (records are fixed-size, so a page costs what it returns whatever
// the log's length). For GET /api/runs/{id}/samples.
struct SampleLogPage {
  SampleLogHeader header;
  std::uint64_t from = 0;           // as asked
  std::vector<SyncSample> samples;  // records from, from + 1, ... up to a corrupt one
  std::uint64_t total_records = 0;  // complete records in the file (from its size)
  std::size_t torn_tail_bytes = 0;  // bytes of an incomplete last record (ignored)
  // A record in the page failed its checksum: the page stops before it, as read_sample_log
  // stops. Records before `from` are not read, so corruption before the page is not seen.
  bool corrupt_record = false;
  std::uint64_t corrupt_at_index = 0;
};

inline constexpr std::size_t kMaxSampleLogPageRecords = std::size_t{1} << 20;  // 96 MiB

// Throws std::runtime_error naming the path and what is wrong with the header, and
// std::invalid_argument when count > kMaxSampleLogPageRecords. A page past the end is empty.
SampleLogPage read_sample_log_page(const std::filesystem::path& path, std::uint64_t from,
                                   std::size_t count);

// Encoding, exposed for tests and tools that check the bytes. Version 1 when header.version
// is 1 (then without extra channels), else version 2.
std::vector<unsigned char> encode_sample_log_header(const SampleLogHeader& header);
std::vector<unsigned char> encode_sample_record(const SyncSample& sample,
                                                std::size_t extra_channels = 0);

}  // namespace wavebench::storage
