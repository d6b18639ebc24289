#pragma once
// A sample log read through in pages, for reports of records of any length: one page of
// records in memory at a time (storage::read_sample_log_page reads only the records it
// returns), never the whole log as structs.
//
//   const auto end = report::scan_sample_log(path, 0, records, [&](const storage::SyncSample& s) {
//     ...  // every intact record from 0 up to `records`, in order
//   });

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <type_traits>

#include "wavebench/storage/sample_log.hpp"

namespace wavebench::report {

// 32 Ki records: about 3 MB of file and 5 MB of structs per page, few enough calls that the
// header read per page does not count.
inline constexpr std::size_t kScanPageRecords = std::size_t{1} << 15;

// Calls visit(sample) for the records [from, end) in order and returns the index after the last
// one visited: `end`, or the first corrupt record's index, or the log's length when it holds
// fewer. A visitor returning bool stops the scan by returning false (that record counts as
// visited). Throws as storage::read_sample_log_page.
template <class Visit>
std::uint64_t scan_sample_log(const std::filesystem::path& path, std::uint64_t from,
                              std::uint64_t end, Visit&& visit,
                              std::size_t page_records = kScanPageRecords) {
  while (from < end) {
    const auto want = static_cast<std::size_t>(
        end - from < page_records ? end - from : std::uint64_t{page_records});
    const auto page = storage::read_sample_log_page(path, from, want);
    for (const auto& s : page.samples) {
      ++from;
      if constexpr (std::is_same_v<decltype(visit(s)), bool>) {
        if (!visit(s)) return from;
      } else {
        visit(s);
      }
    }
    if (page.samples.size() < want) break;  // the log's end or a corrupt record
  }
  return from;
}

}  // namespace wavebench::report
