#include "wavebench/daemon/sample_json.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace wavebench::daemon {

namespace {

template <typename T>
T required(const nlohmann::json& json, const char* key) {
  const auto it = json.find(key);
  if (it == json.end() || !it->is_number()) {
    throw std::invalid_argument(std::string("sample: ") + key + ": got " +
                                (it == json.end() ? std::string("nothing") : it->dump()) +
                                ", expected a number");
  }
  return it->get<T>();
}

// As nlohmann::json dumps a double: the shortest text that reads back the same, with ".0" on a
// whole number so it stays a float; null when not finite.
void append_double(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  const std::string_view text(buf, static_cast<std::size_t>(end - buf));
  out += text;
  if (text.find_first_of(".e") == std::string_view::npos) out += ".0";
}

template <typename T>
void append_integer(std::string& out, T v) {
  char buf[24];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, end);
}

}  // namespace

void append_sample_json(std::string& out, const storage::SyncSample& sample,
                        std::span<const std::string> extra_keys) {
  out += "{\"index\":";
  append_integer(out, sample.index);
  out += ",\"sync_counter\":";
  append_integer(out, sample.sync_counter);
  out += ",\"flags\":";
  append_integer(out, sample.flags);
  out += ",\"receive_time_ns\":";
  append_integer(out, sample.receive_time_ns);
  out += ",\"missed_before\":";
  append_integer(out, sample.missed_before);
  for (const auto& c : storage::kCoreChannels) {
    out += ",\"";
    out += c.column;
    out += "\":";
    if (sample.valid(c.valid)) {
      append_double(out, sample.*c.value);
    } else {
      out += "null";
    }
  }
  if (!extra_keys.empty()) {
    out += ",\"extra\":{";
    for (std::size_t i = 0; i < extra_keys.size() && i < storage::kMaxExtraChannels; ++i) {
      if (i > 0) out += ',';
      out += extra_keys[i];
      out += ':';
      if (sample.extra_arrived(i)) {
        append_double(out, sample.extra[i]);
      } else {
        out += "null";
      }
    }
    out += '}';
  }
  out += '}';
}

nlohmann::json sample_to_json(const storage::SyncSample& sample,
                              std::span<const storage::ChannelInfo> extra) {
  nlohmann::json j = {{"index", sample.index},
                      {"sync_counter", sample.sync_counter},
                      {"flags", sample.flags},
                      {"receive_time_ns", sample.receive_time_ns},
                      {"missed_before", sample.missed_before}};
  for (const auto& c : storage::kCoreChannels) {
    j[c.column] = sample.valid(c.valid) ? nlohmann::json(sample.*c.value) : nlohmann::json(nullptr);
  }
  if (!extra.empty()) {
    nlohmann::json e = nlohmann::json::object();
    for (std::size_t i = 0; i < extra.size() && i < storage::kMaxExtraChannels; ++i)
      e[extra[i].name] =
          sample.extra_arrived(i) ? nlohmann::json(sample.extra[i]) : nlohmann::json(nullptr);
    j["extra"] = std::move(e);
  }
  return j;
}

nlohmann::json channels_to_json(std::span<const storage::ChannelInfo> extra) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& c : storage::core_channels())
    list.push_back({{"name", c.name}, {"unit", c.unit}, {"extra", false}});
  for (const auto& c : extra) list.push_back({{"name", c.name}, {"unit", c.unit}, {"extra", true}});
  return list;
}

storage::SyncSample sample_from_json(const nlohmann::json& json,
                                     std::span<const storage::ChannelInfo> extra) {
  if (!json.is_object()) {
    throw std::invalid_argument("sample: got " + json.dump() + ", expected an object");
  }
  storage::SyncSample s;
  s.index = required<std::uint64_t>(json, "index");
  s.sync_counter = required<std::uint32_t>(json, "sync_counter");
  s.flags = required<std::uint32_t>(json, "flags");
  s.receive_time_ns = required<std::int64_t>(json, "receive_time_ns");
  s.missed_before = required<std::uint32_t>(json, "missed_before");
  for (const auto& c : storage::kCoreChannels) {
    const auto it = json.find(c.column);
    if (it != json.end() && it->is_number()) s.*c.value = it->get<double>();
  }
  const auto e = json.find("extra");
  if (e != json.end() && e->is_object()) {
    for (std::size_t i = 0; i < extra.size() && i < storage::kMaxExtraChannels; ++i) {
      const auto v = e->find(extra[i].name);
      if (v != e->end() && v->is_number()) {
        s.extra[i] = v->get<double>();
        s.extra_valid |= 1U << i;
      }
    }
  }
  return s;
}

}  // namespace wavebench::daemon
