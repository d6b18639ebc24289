#pragma once
// SyncSample as JSON for the API: channels by name, a channel that did not arrive is null.
// The client turns it back into a SyncSample for export.

#include <nlohmann/json.hpp>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::daemon {

nlohmann::json sample_to_json(const storage::SyncSample& sample);
// Throws std::invalid_argument naming the key when a field is missing or of the wrong type.
storage::SyncSample sample_from_json(const nlohmann::json& json);

}  // namespace wavebench::daemon
