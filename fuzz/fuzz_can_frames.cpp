// Every decoder that takes a frame off the bus, fed arbitrary frames and candump text.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "wavebench/can/error_frame.hpp"
#include "wavebench/can/frame.hpp"
#include "wavebench/canopen/cia402.hpp"
#include "wavebench/canopen/emcy.hpp"
#include "wavebench/canopen/frame_description.hpp"
#include "wavebench/canopen/nmt.hpp"
#include "wavebench/canopen/pdo.hpp"
#include "wavebench/canopen/value_text.hpp"

namespace wc = wavebench::can;
namespace co = wavebench::canopen;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  wc::Frame f;
  f.id = static_cast<std::uint32_t>(data[0] | (data[1] << 8)) & 0x7FF;
  const std::uint8_t flags = data[2];
  f.extended = (flags & 0x80) != 0;
  f.rtr = (flags & 0x40) != 0;
  f.error = (flags & 0x20) != 0;
  if (f.extended || f.error) f.id |= static_cast<std::uint32_t>(flags & 0x1F) << 24;
  f.len = static_cast<std::uint8_t>(flags & 0x0F);  // may exceed 8: decoders must clamp
  for (std::size_t i = 0; i < 8 && 3 + i < size; ++i) f.data[i] = data[3 + i];
  if (f.len > 8) f.len = 8;  // Frame's invariant; the bus never delivers more

  (void)wc::to_string(f);
  (void)wc::classify_error_frame(f);
  (void)co::describe_frame(f);
  (void)co::decode_heartbeat(f);
  (void)co::decode_emcy(f);
  const auto sw = static_cast<std::uint16_t>(f.data[0] | (f.data[1] << 8));
  (void)co::describe_statusword(sw);
  (void)co::controlword_toward(co::decode_state(sw), co::Cia402State::operation_enabled);
  (void)co::format_value("", f.payload());

  // A layout from the fuzz bytes, then decode the frame with it.
  try {
    std::vector<co::PdoEntry> entries;
    for (std::size_t i = 11; i + 1 < size && entries.size() < 8; i += 2) {
      entries.push_back(
          {0x6000, static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(data[i] % 65)});
    }
    co::PdoLayout layout(entries);
    if (layout.fits(f)) {
      for (std::size_t i = 0; i < layout.size(); ++i) {
        (void)layout.raw(f, i);
        (void)layout.signed_value(f, i);
      }
    }
  } catch (const std::invalid_argument&) {
  }

  // The same bytes as candump/cansend text.
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (auto parsed = wc::parse_frame(text)) {
    const auto again = wc::parse_frame(wc::to_string(*parsed));
    if (!again || !(*again == *parsed)) __builtin_trap();  // round trip must hold
  }
  for (const char* type : {"u8", "i16", "u32", "i64", "f32", "f64", "hex", "str"}) {
    try {
      const auto bytes = co::encode_value(type, text);
      (void)co::format_value(type, bytes);
    } catch (const std::invalid_argument&) {
    }
  }
  return 0;
}
