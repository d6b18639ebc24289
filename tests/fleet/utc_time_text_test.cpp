// The SQLite store's one form of a time: what a user types for --from/--to, and what the run
// index writes, compare as the times do.
#include "wavebench/fleet/utc_time_text.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace wavebench::fleet {
namespace {

TEST(UtcTimeText, DatesTimesAndOffsetsToOneForm) {
  EXPECT_EQ(canonical_utc("2026-11-24", "from"), "2026-11-24T00:00:00.000000Z");
  EXPECT_EQ(canonical_utc("2026-11-24T10:15", "from"), "2026-11-24T10:15:00.000000Z");
  EXPECT_EQ(canonical_utc("2026-11-24 10:15:30Z", "from"), "2026-11-24T10:15:30.000000Z");
  EXPECT_EQ(canonical_utc("2026-11-24T10:15:30.123456Z", "from"), "2026-11-24T10:15:30.123456Z");
  EXPECT_EQ(canonical_utc("2026-11-24T10:15:30.5Z", "from"), "2026-11-24T10:15:30.500000Z");
  // An offset east of UTC across midnight and a year.
  EXPECT_EQ(canonical_utc("2027-01-01T01:30:00+02:00", "to"), "2026-12-31T23:30:00.000000Z");
  EXPECT_EQ(canonical_utc("2026-11-24T22:00:00-0530", "to"), "2026-11-25T03:30:00.000000Z");
}

TEST(UtcTimeText, LeapDaysAndMonthEndsAreDates) {
  EXPECT_EQ(canonical_utc("2028-02-29", "from"), "2028-02-29T00:00:00.000000Z");
  EXPECT_EQ(canonical_utc("2000-02-29", "from"), "2000-02-29T00:00:00.000000Z");
  EXPECT_EQ(canonical_utc("2026-12-31T23:59:59", "to"), "2026-12-31T23:59:59.000000Z");
}

TEST(UtcTimeText, ALeapSecondWhereOneIsInsertedSortsAtTheEndOfItsMinute) {
  EXPECT_EQ(canonical_utc("2016-12-31T23:59:60Z", "from"), "2016-12-31T23:59:59.999999Z");
  EXPECT_EQ(canonical_utc("2015-06-30T23:59:60Z", "from"), "2015-06-30T23:59:59.999999Z");
  EXPECT_EQ(canonical_utc("2016-12-31T18:59:60-05:00", "from"), "2016-12-31T23:59:59.999999Z");
  // It once became "10000-01-01T...", text that sorted before every run.
  EXPECT_EQ(canonical_utc("9999-12-31T23:59:60Z", "from"), "9999-12-31T23:59:59.999999Z");
  EXPECT_EQ(canonical_utc("2026-11-24T10:00:00+23:59", "from"), "2026-11-23T10:01:00.000000Z");
}

TEST(UtcTimeText, RefusesOtherTextNamingTheKey) {
  for (const std::string bad :
       {"", "yesterday", "2026-13-01", "2026-11-24T25:00", "2026-11-24T", "2026-11-24T10:15:30.Z",
        "2026-11-24 junk", "24.11.2026",
        // days past the month's end, not carried into the next month
        "2026-02-29", "2026-04-31", "2100-02-29", "0999-12-31",
        // issue #22: RFC 3339's bounds
        "2026-11-24T10:00:00+24:00", "2026-11-24T10:00:00-00:60", "2026-11-24T12:30:60Z",
        "2026-06-30T23:59:60+01:00", "9999-12-31T23:59:59-01:00", "1000-01-01T00:30:00+01:00"}) {
    try {
      canonical_utc(bad, "from");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("from: got '" + bad + "'"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace wavebench::fleet
