#pragma once
// A stored run's samples as a download, in the formats of `wavebench export`
// (wavebench/exports/sample_export.hpp):
//
//   GET /api/runs/{id}/export?format=mat|hdf5|csv|json[&partial=1]
//       the file (Content-Disposition: attachment; RUN_ID-samples.mat, ...); a running run
//       only with partial=1 (409 otherwise), and then marked partial in the file
//
// Sent in chunks (body_chunks.hpp) with bounded memory and scratch (issue #22: one download of
// a 254 MB log took 1 GB of RAM and 0.7 GB of /tmp):
//  - csv and json of a finished run are made one page of samples per chunk, straight from
//  samples.wbs to the
//    socket: no scratch file, one page in memory;
//  - mat and hdf5 (and a partial export, which the export library marks) need a whole file (a MAT
//  variable is written whole, HDF5 seeks): it is built
//    once in a scratch folder, after checking that the scratch disk has room for it, then
//    unlinked while open and sent from the open file, so nothing is left behind even when the
//    client goes away. Their log is bounded by kMaxExportDownloadLogBytes (the scratch bound).
// A bad format is 400 naming the key, the value and what was expected. What the query asks for
// is read in one place (ExportRequest in the .cpp): a new flag goes there. The caller limits how
// many run at once and who may ask (daemon_api.cpp).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "wavebench/daemon/daemon_api.hpp"
#include "wavebench/daemon/http_target.hpp"
#include "wavebench/storage/run_store.hpp"

namespace wavebench::daemon {

inline constexpr std::uintmax_t kMaxExportDownloadLogBytes = std::uintmax_t{256} << 20;
// Free space kept on the scratch disk beyond the estimated file.
inline constexpr std::uintmax_t kScratchReserveBytes = std::uintmax_t{64} << 20;
inline constexpr std::size_t kExportChunkRecords = 4096;  // csv/json: about 0.5 MiB of text
inline constexpr std::size_t kExportFileChunkBytes = 256 << 10;

// `id` is a run id (checked by the caller) of `store`. `slot` is held until the last chunk is
// sent (the caller's count of downloads in progress). `scratch_dir`: where mat/hdf5 files are
// built (empty: the system's temporary folder).
ApiResponse run_export_download(const storage::RunStore& store, const std::string& id,
                                const HttpTarget& target, std::shared_ptr<void> slot = nullptr,
                                const std::filesystem::path& scratch_dir = {});

}  // namespace wavebench::daemon
