// Text below the EDS reader: case, whitespace, UTF-8 and Latin-1, bounded warnings.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "eds_detail.hpp"

namespace wavebench::canopen::eds_detail {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string_view trim(std::string_view s) {
  // ASCII whitespace only: a Latin-1 0xA0 converted to UTF-8 is part of a name, not space.
  auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
  };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

std::string clip(std::string_view s, std::size_t max) {
  if (s.size() <= max) return std::string(s);
  std::size_t end = max;
  // Back off UTF-8 continuation bytes (10xxxxxx) so the cut is between characters.
  while (end > 0 && (static_cast<unsigned char>(s[end]) & 0xC0) == 0x80) --end;
  return std::string(s.substr(0, end)) + "...";
}

bool valid_utf8(std::string_view s) noexcept {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    std::uint32_t cp = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1;
      cp = c & 0x1FU;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2;
      cp = c & 0x0FU;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3;
      cp = c & 0x07U;
    } else {
      return false;
    }
    if (s.size() - i <= n) return false;
    for (std::size_t k = 1; k <= n; ++k) {
      const auto cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return false;
      cp = cp << 6 | (cc & 0x3FU);
    }
    // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8.
    constexpr std::uint32_t kMin[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF) return false;
    i += n + 1;
  }
  return true;
}

std::string to_utf8(std::string_view text) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  if (valid_utf8(text)) return std::string(text);
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else {  // Latin-1 is the first 256 code points: two UTF-8 bytes each.
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string value_message(std::string_view source, std::string_view section, std::string_view key,
                          std::string_view value, std::string_view expected) {
  return fmt::format("EDS {}: [{}] {} = '{}': expected {}", source, clip(section), clip(key),
                     clip(value), expected);
}

std::string Warnings::add(std::string text) {
  if (list_.size() < max_) {
    list_.push_back(text);
  } else {
    ++dropped_;
  }
  return text;
}

std::string Warnings::value(std::string_view section, std::string_view key, std::string_view value,
                            std::string_view expected) {
  return add(value_message(source_, section, key, value, expected));
}

std::string Warnings::section(std::string_view section, std::string_view what) {
  return add(fmt::format("EDS {}: [{}]: {}", source_, clip(section), what));
}

std::string Warnings::line(std::size_t line, std::string_view what) {
  return add(fmt::format("EDS {}: line {}: {}", source_, line, what));
}

std::vector<std::string> Warnings::take() {
  if (dropped_ > 0)
    list_.push_back(fmt::format("EDS {}: {} more warnings not listed", source_, dropped_));
  dropped_ = 0;
  return std::move(list_);
}

}  // namespace wavebench::canopen::eds_detail
