#include "wavebench/storage/channel_info.hpp"

#include <algorithm>
#include <stdexcept>

#include "wavebench/storage/sync_sample.hpp"

namespace wavebench::storage {

std::span<const ChannelInfo> core_channels() {
  static const std::vector<ChannelInfo> channels = [] {
    std::vector<ChannelInfo> out;
    for (const auto& c : kCoreChannels) out.push_back({std::string(c.name), std::string(c.unit)});
    return out;
  }();
  return channels;
}

void check_extra_channels(std::span<const ChannelInfo> extra) {
  if (extra.size() > kMaxExtraChannels)
    throw std::invalid_argument(std::to_string(extra.size()) +
                                " extra channels; expected at most " +
                                std::to_string(kMaxExtraChannels));
  std::vector<std::string> seen;
  for (const auto& c : core_channels()) seen.push_back(c.name);
  for (const auto& c : extra) {
    const bool name_ok = !c.name.empty() && c.name.size() <= kMaxChannelNameBytes &&
                         std::all_of(c.name.begin(), c.name.end(), [](char ch) {
                           return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
                         });
    if (!name_ok)
      throw std::invalid_argument("channel name '" + c.name + "': expected 1.." +
                                  std::to_string(kMaxChannelNameBytes) + " of [a-z0-9_]");
    const bool unit_ok =
        !c.unit.empty() && c.unit.size() <= kMaxChannelUnitBytes &&
        std::all_of(c.unit.begin(), c.unit.end(), [](char ch) { return ch > ' ' && ch < 0x7f; });
    if (!unit_ok)
      throw std::invalid_argument("channel '" + c.name + "': unit '" + c.unit + "': expected 1.." +
                                  std::to_string(kMaxChannelUnitBytes) + " printable characters");
    if (std::find(seen.begin(), seen.end(), c.name) != seen.end())
      throw std::invalid_argument("channel name '" + c.name + "' is used twice");
    seen.push_back(c.name);
  }
}

}  // namespace wavebench::storage
