#pragma once
// A stored run's samples as a download, in the formats of `wavebench export`
// (wavebench/exports/sample_export.hpp):
//
//   GET /api/runs/{id}/export?format=mat|hdf5|csv|json
//       the file (Content-Disposition: attachment; RUN_ID-samples.mat, ...), written from
//       pages of samples.wbs into a temporary folder and removed once read back
//
// The answer is sent whole (the HTTP layer has no streamed bodies but server-sent events), so
// a log larger than kMaxExportDownloadLogBytes is refused with 413 pointing at `wavebench
// export`, which pages through the samples API instead. A bad format is 400 naming the key,
// the value and what was expected.

#include <cstdint>
#include <filesystem>
#include <string>

#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

inline constexpr std::uintmax_t kMaxExportDownloadLogBytes = std::uintmax_t{256} << 20;

// `id` is a run id (checked by the caller) of `store`.
ApiResponse run_export_download(const storage::RunStore& store, const std::string& id,
                                const HttpTarget& target);

}  // namespace wavebench::daemon
