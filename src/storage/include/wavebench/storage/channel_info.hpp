#pragma once
// The name and SI unit of a sample channel, as the sample log's header and the API list them.

#include <span>
#include <string>
#include <vector>

namespace wavebench::storage {

struct ChannelInfo {
  std::string name;  // [a-z0-9_], at most kMaxChannelNameBytes bytes
  std::string unit;  // SI, e.g. "rad", "N*m", at most kMaxChannelUnitBytes bytes
  bool operator==(const ChannelInfo&) const = default;
};

inline constexpr std::size_t kMaxChannelNameBytes = 31;
inline constexpr std::size_t kMaxChannelUnitBytes = 15;

// kCoreChannels' names and units, in its order (sync_sample.hpp).
std::span<const ChannelInfo> core_channels();

// Throws std::invalid_argument naming the channel when a name or unit is empty, too long or
// not [a-z0-9_] (units: printable ASCII), or a name repeats one before it (core ones included).
void check_extra_channels(std::span<const ChannelInfo> extra);

}  // namespace wavebench::storage
