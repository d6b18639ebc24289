#pragma once
// The SDO server of a simulated node (CiA 301 §7.2.4): expedited and segmented download and
// upload over raw 8-byte payloads. Block transfer is not offered (answered with 05040001).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "wavebench/simdevices/object_dictionary.hpp"

namespace wavebench::simdevices {

using SdoPayload = std::array<std::uint8_t, 8>;

class SdoServer {
 public:
  // `timeout_s`: a segmented transfer idle longer than this is aborted with 05040000.
  explicit SdoServer(ObjectDictionary& od, double timeout_s = 1.0)
      : od_(od), timeout_s_(timeout_s) {}

  // One request from the client at time `now` [s]; returns the response, if any (an abort
  // request from the client gets none). Payloads shorter than 8 bytes are zero-padded.
  std::optional<SdoPayload> handle(std::span<const std::uint8_t> request, double now);

  // Aborts a segmented transfer that has been idle past the timeout; returns the abort frame.
  std::optional<SdoPayload> poll_timeout(double now);

  void reset() { state_ = State::kIdle; }

  static SdoPayload abort_payload(std::uint16_t index, std::uint8_t sub, std::uint32_t code);

 private:
  enum class State { kIdle, kDownloading, kUploading };

  SdoPayload initiate_download(const SdoPayload& req);
  SdoPayload download_segment(const SdoPayload& req);
  SdoPayload initiate_upload(const SdoPayload& req);
  SdoPayload upload_segment(const SdoPayload& req);
  SdoPayload abort_transfer(std::uint32_t code);

  ObjectDictionary& od_;
  double timeout_s_;
  State state_ = State::kIdle;
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0;
  bool toggle_ = false;
  std::optional<std::size_t> expected_size_;
  std::vector<std::uint8_t> buffer_;
  std::size_t offset_ = 0;
  double last_activity_ = 0;
};

}  // namespace wavebench::simdevices
