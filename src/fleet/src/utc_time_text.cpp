#include "wavebench/fleet/utc_time_text.hpp"

#include <cctype>
#include <cstdio>
#include <ctime>
#include <stdexcept>

namespace wavebench::fleet {

namespace {

// Reads `n` digits at `at`; false when they are not there.
bool digits(const std::string& s, std::size_t& at, std::size_t n, int& value) {
  if (at + n > s.size()) return false;
  value = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const char c = s[at + i];
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    value = value * 10 + (c - '0');
  }
  at += n;
  return true;
}

bool take(const std::string& s, std::size_t& at, char c) {
  if (at < s.size() && s[at] == c) {
    ++at;
    return true;
  }
  return false;
}

}  // namespace

std::string canonical_utc(const std::string& text, const std::string& key) {
  const auto refuse = [&] {
    return std::invalid_argument(key + ": got '" + text +
                                 "', expected an ISO 8601 date or time (2026-11-24, "
                                 "2026-11-24T10:15:00Z)");
  };
  const auto refuse_because = [&](const std::string& expected) {
    return std::invalid_argument(key + ": got '" + text + "', expected " + expected);
  };
  std::size_t at = 0;
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  long micros = 0;
  if (!digits(text, at, 4, year) || !take(text, at, '-') || !digits(text, at, 2, month) ||
      !take(text, at, '-') || !digits(text, at, 2, day)) {
    throw refuse();
  }
  if (take(text, at, 'T') || take(text, at, ' ')) {
    if (!digits(text, at, 2, hour) || !take(text, at, ':') || !digits(text, at, 2, minute)) {
      throw refuse();
    }
    if (take(text, at, ':')) {
      if (!digits(text, at, 2, second)) throw refuse();
      if (take(text, at, '.')) {
        long scale = 100000;
        const std::size_t first = at;
        while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at]))) {
          micros += (text[at] - '0') * scale;  // beyond microseconds: truncated, as the index
          scale /= 10;
          ++at;
        }
        if (at == first) throw refuse();
      }
    }
  }
  int offset_minutes = 0;
  if (at < text.size() && (text[at] == '+' || text[at] == '-')) {
    const int sign = text[at++] == '+' ? 1 : -1;
    int oh = 0, om = 0;
    if (!digits(text, at, 2, oh)) throw refuse();
    if (take(text, at, ':') || (at < text.size() && text[at] != 'Z')) {
      if (!digits(text, at, 2, om)) throw refuse();
    }
    // RFC 3339: an offset is at most 23:59 either way ("+24:00" names no zone).
    if (oh > 23 || om > 59) throw refuse_because("an offset from -23:59 to +23:59");
    offset_minutes = sign * (oh * 60 + om);
  } else {
    take(text, at, 'Z');
  }
  // Days past the month's end (2026-02-31) are refused as PostgreSQL refuses them, not carried
  // into the next month; years before 1000 would not sort as text.
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (at != text.size() || year < 1000 || month < 1 || month > 12 || day < 1 ||
      day > kDays[month - 1] + (month == 2 && leap ? 1 : 0) || hour > 23 || minute > 59 ||
      second > 60) {
    throw refuse();
  }
  std::tm tm{};
  tm.tm_year = year - 1900;
  tm.tm_mon = month - 1;
  tm.tm_mday = day;
  tm.tm_hour = hour;
  tm.tm_min = minute;
  tm.tm_sec = second;
  const std::time_t t = ::timegm(&tm) - static_cast<std::time_t>(offset_minutes) * 60;
  std::tm utc{};
  gmtime_r(&t, &utc);
  if (second == 60) {
    // A leap second is inserted only as 23:59:60 UTC at the end of June or December (RFC 3339
    // 5.7); timegm() carried it into the next minute, so that minute is 00:00 on the 1st of July
    // or January. It is kept as the last microsecond of 23:59:59, so it sorts where it happened.
    if (!(utc.tm_hour == 0 && utc.tm_min == 0 && utc.tm_sec == 0 && utc.tm_mday == 1 &&
          (utc.tm_mon == 0 || utc.tm_mon == 6))) {
      throw refuse_because("a leap second (:60) only at 23:59:60 UTC on June 30 or December 31");
    }
    const std::time_t before = t - 1;
    gmtime_r(&before, &utc);
    micros = 999999;
  }
  // Text of another width would not sort as the times do ("10000-..." before "2026-...").
  if (utc.tm_year + 1900 < 1000 || utc.tm_year + 1900 > 9999) {
    throw refuse_because("a time from year 1000 to 9999 in UTC");
  }
  char buf[40];
  const auto n = std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(buf + n, sizeof buf - n, ".%06ldZ", micros);
  return buf;
}

}  // namespace wavebench::fleet
