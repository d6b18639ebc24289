#include "wavebench/canopen/sdo_abort.hpp"

#include <gtest/gtest.h>

namespace wavebench::canopen {
namespace {

TEST(SdoAbortText, SpecCodesComeOutAsText) {
  EXPECT_EQ(abort_text(0x05040000), "05040000 SDO protocol timed out");
  EXPECT_EQ(abort_text(0x06010000), "06010000 unsupported access to an object");
  EXPECT_EQ(abort_text(0x06010002), "06010002 attempt to write a read only object");
  EXPECT_EQ(abort_text(0x06020000), "06020000 object does not exist in the object dictionary");
  EXPECT_NE(abort_text(0x06040041).find("cannot be mapped"), std::string::npos);
  EXPECT_NE(abort_text(0x06040042).find("exceed PDO length"), std::string::npos);
  EXPECT_NE(abort_text(0x06070010).find("length of service parameter does not match"),
            std::string::npos);
  EXPECT_EQ(abort_text(0x06090011), "06090011 sub-index does not exist");
  EXPECT_NE(abort_text(0x06090030).find("invalid value"), std::string::npos);
  EXPECT_EQ(abort_text(0x08000000), "08000000 general error");
  EXPECT_NE(abort_text(0x08000021).find("local control"), std::string::npos);
  EXPECT_NE(abort_text(0x08000022).find("present device state"), std::string::npos);
  EXPECT_EQ(abort_text(0x12345678), "12345678 unknown abort code");
}

TEST(SdoAbortText, ErrorCodesRoundTrip) {
  const std::error_code ec = SdoAbort::no_sub_index;
  EXPECT_EQ(ec.category().name(), std::string("sdo"));
  EXPECT_EQ(abort_code_of(ec), 0x06090011U);
  EXPECT_EQ(abort_code_of(std::make_error_code(std::errc::timed_out)), 0x05040000U);
  const SdoError err(ec, 3, 0x1018, 9);
  EXPECT_NE(std::string(err.what()).find("node 3 object 1018:09"), std::string::npos) << err.what();
}

}  // namespace
}  // namespace wavebench::canopen
