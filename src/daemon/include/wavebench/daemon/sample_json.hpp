#pragma once
// SyncSample as JSON for the API: channels by name, a channel that did not arrive is null.
// The client turns it back into a SyncSample for export.

#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "wavebench/storage/channel_info.hpp"
#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::daemon {

// The bench's extra channels go under "extra", keyed by their names (null when not arrived).
nlohmann::json sample_to_json(const storage::SyncSample& sample,
                              std::span<const storage::ChannelInfo> extra = {});
// The object sample_to_json gives, appended to `out` as JSON text. `extra_keys`: the extra
// channels' names, each already a JSON string (json(name).dump()). A page of 10,000 samples
// is text in a few milliseconds where building the objects first takes tens (issue #12).
void append_sample_json(std::string& out, const storage::SyncSample& sample,
                        std::span<const std::string> extra_keys = {});
// Throws std::invalid_argument naming the key when a field is missing or of the wrong type.
storage::SyncSample sample_from_json(const nlohmann::json& json,
                                     std::span<const storage::ChannelInfo> extra = {});
// {"name", "unit"} of the core and the extra channels, for the API's "channels" lists.
nlohmann::json channels_to_json(std::span<const storage::ChannelInfo> extra);

}  // namespace wavebench::daemon
