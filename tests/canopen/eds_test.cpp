// The CiA 306 EDS reader: sections, sub-indices, numbers, $NODEID, and hostile files.
#include "wavebench/canopen/eds.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "wavebench/canopen/cia402_drive.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::canopen {
namespace {

const char* kSmall = R"(; a comment line
[FileInfo]
FileName=small.eds

[DeviceInfo]
VendorNumber=0x00000A57
ProductNumber=1026

[MandatoryObjects]
SupportedObjects=2
1=0x1000
2=0x1018

[1000]
ParameterName=Device type
ObjectType=0x7
DataType=0x0007
AccessType=const
DefaultValue=0x00020192
PDOMapping=0

[1018]
ParameterName=Identity
ObjectType=0x9
SubNumber=2

[1018sub0]
ParameterName=Highest sub-index
DataType=0x0005
AccessType=const
DefaultValue=1

[1018sub1]
ParameterName=Vendor-ID
DataType=0x0007
AccessType=ro
DefaultValue=0xA57

[1800]
ParameterName=TPDO1 communication
ObjectType=0x9
SubNumber=1

[1800sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=RW
DefaultValue=$NODEID+0x180

[6041]
parametername=Statusword
DATATYPE=0x0006
AccessType=ro
PDOMapping=1
LowLimit=0
HighLimit=0xFFFF
)";

std::string with(const std::string& section_and_keys) {
  return std::string(kSmall) + "\n" + section_and_keys + "\n";
}

std::string error_of(const std::string& text) {
  try {
    Eds::parse(text, "test.eds");
  } catch (const EdsError& e) {
    return e.what();
  }
  return "";
}

// The warnings of a file that must read, one a line.
std::string warnings_of(const std::string& text) {
  std::string out;
  const auto eds = Eds::parse(text, "test.eds");
  for (const auto& w : eds.warnings()) out += w + "\n";
  return out;
}

TEST(Eds, ReadsVarsRecordsSubIndicesAndDeviceInfo) {
  const auto eds = Eds::parse(kSmall, "small.eds");
  ASSERT_NE(eds.find(0x1000, 0), nullptr);
  EXPECT_EQ(eds.find(0x1000, 0)->data_type, datatype::kUnsigned32);
  EXPECT_EQ(eds.find(0x1000, 0)->access, EdsAccess::kConst);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x1000, 0)), 0x00020192);
  ASSERT_NE(eds.find(0x1018, 1), nullptr);
  EXPECT_EQ(eds.find(0x1018, 1)->object_type, kObjectRecord);
  EXPECT_EQ(eds.find(0x1018, 1)->name, "Vendor-ID");
  EXPECT_EQ(eds.find(0x1018, 2), nullptr);
  // Keys are case-insensitive; PDOMapping and limits kept.
  const auto* sw = eds.find(0x6041, 0);
  ASSERT_NE(sw, nullptr);
  EXPECT_EQ(sw->name, "Statusword");
  EXPECT_TRUE(sw->pdo_mapping);
  EXPECT_EQ(sw->high_limit.value_or(""), "0xFFFF");
  EXPECT_EQ(eds.find(0x1800, 1)->access, EdsAccess::kRw);
  EXPECT_EQ(eds.vendor_number(), 0xA57U);
  EXPECT_EQ(eds.product_number(), 1026U);
  EXPECT_FALSE(eds.revision_number());
  EXPECT_TRUE(eds.has_index(0x1018));
  EXPECT_FALSE(eds.has_index(0x1001));
}

TEST(Eds, NodeIdExpressions) {
  const auto eds = Eds::parse(kSmall, "small.eds");
  EXPECT_EQ(*eds.default_integer(*eds.find(0x1800, 1), 5), 0x185);
  EXPECT_EQ(parse_eds_integer("$NODEID", 7), 7);
  EXPECT_EQ(parse_eds_integer("0x80+$nodeid", 3), 0x83);
  EXPECT_EQ(parse_eds_integer(" $NODEID + 0x200 ", 1), 0x201);
  EXPECT_EQ(parse_eds_integer("-12"), -12);
  EXPECT_EQ(parse_eds_integer("010"), 8);  // CiA 306: a leading 0 is octal
  EXPECT_EQ(parse_eds_integer("0"), 0);
  for (const char* bad : {"$NODEI+1", "$NODEID*2", "$NODEID+", "1+$NODEID+2", "$NODEID-1",
                          "$NODEID+$NODEID", "0xZZ", "12abc", "", "08", "99999999999999999999"}) {
    EXPECT_THROW(parse_eds_integer(bad, 1), std::invalid_argument) << bad;
  }
}

TEST(EdsHostile, BadNodeIdExpressionIsAWarningNamingFileSectionKeyAndValue) {
  const auto text =
      with("[6060]\nParameterName=Mode\nDataType=0x0002\nAccessType=rw\nDefaultValue=$NODEID*2");
  const auto w = warnings_of(text);
  EXPECT_NE(w.find("test.eds"), std::string::npos) << w;
  EXPECT_NE(w.find("[6060]"), std::string::npos) << w;
  EXPECT_NE(w.find("DefaultValue"), std::string::npos) << w;
  EXPECT_NE(w.find("$NODEID*2"), std::string::npos) << w;
  // The object stays, without the value.
  const auto eds = Eds::parse(text, "test.eds");
  ASSERT_NE(eds.find(0x6060, 0), nullptr);
  EXPECT_EQ(eds.find(0x6060, 0)->default_value, "");
  EXPECT_FALSE(eds.default_integer(*eds.find(0x6060, 0)));
}

TEST(EdsHostile, MissingKeysAreNamedAndCostTheObjectOnly) {
  auto text = with("[6060]\nParameterName=Mode\nAccessType=rw");
  auto w = warnings_of(text);
  EXPECT_NE(w.find("[6060] DataType"), std::string::npos) << w;
  EXPECT_NE(w.find("missing"), std::string::npos) << w;
  auto eds = Eds::parse(text, "test.eds");
  EXPECT_EQ(eds.find(0x6060, 0), nullptr);
  ASSERT_TRUE(eds.problem(0x6060, 0));
  EXPECT_NE(eds.problem(0x6060, 0)->find("[6060] DataType"), std::string::npos);
  EXPECT_NE(eds.find(0x6041, 0), nullptr);  // the rest of the file is read
  EXPECT_FALSE(eds.problem(0x6041, 0));
  EXPECT_FALSE(eds.problem(0x6099, 0));  // no section: no reason either
  // A missing name is a warning; the object stays.
  w = warnings_of(with("[6060]\nDataType=0x0002\nAccessType=rw"));
  EXPECT_NE(w.find("[6060] ParameterName"), std::string::npos) << w;
  text = with("[6060]\nParameterName=Mode\nDataType=0x0002");
  w = warnings_of(text);
  EXPECT_NE(w.find("[6060] AccessType"), std::string::npos) << w;
  EXPECT_EQ(Eds::parse(text, "test.eds").find(0x6060, 0), nullptr);
  w = warnings_of(with("[2000]\nParameterName=Rec\nObjectType=0x9"));
  EXPECT_NE(w.find("[2000] SubNumber"), std::string::npos) << w;
}

TEST(EdsHostile, BadNumbersAndValuesAreNamed) {
  auto w = warnings_of(with("[6060]\nParameterName=Mode\nDataType=0xG2\nAccessType=rw"));
  EXPECT_NE(w.find("[6060] DataType = '0xG2'"), std::string::npos) << w;
  w = warnings_of(with("[6060]\nParameterName=Mode\nDataType=0x0002\nAccessType=readwrite"));
  EXPECT_NE(w.find("AccessType = 'readwrite': expected ro, wo, rw"), std::string::npos) << w;
  w = warnings_of(with("[6060]\nParameterName=Mode\nDataType=0x0002\nAccessType=rw\nPDOMapping=2"));
  EXPECT_NE(w.find("PDOMapping = '2'"), std::string::npos) << w;
  w = warnings_of(with("[6060]\nParameterName=Mode\nDataType=0x0002\nAccessType=rw\nLowLimit=low"));
  EXPECT_NE(w.find("LowLimit = 'low'"), std::string::npos) << w;
  w = warnings_of(
      with("[2001]\nParameterName=R\nDataType=0x0008\nAccessType=ro\nDefaultValue=1.5e"));
  EXPECT_NE(w.find("a finite real number"), std::string::npos) << w;
  w = warnings_of(with("[2002]\nParameterName=V\nObjectType=0x4\nDataType=0x0007\nAccessType=ro"));
  EXPECT_NE(w.find("[2002] ObjectType = '0x4'"), std::string::npos) << w;
  w = warnings_of(with("[2003]\nParameterName=V\nDataType=0x10000\nAccessType=ro"));
  EXPECT_NE(w.find("DataType = '0x10000'"), std::string::npos) << w;
  // A value outside its type's range.
  w = warnings_of(
      with("[2004]\nParameterName=V\nDataType=0x0005\nAccessType=ro\nDefaultValue=256"));
  EXPECT_NE(w.find("[2004] DefaultValue = '256': expected UNSIGNED8 in 0..255"), std::string::npos)
      << w;
}

TEST(EdsHostile, StructureErrorsAreWarningsNamingSectionAndKey) {
  // A sub-index without its record, a record whose SubNumber disagrees, duplicates.
  auto text = with("[2100sub1]\nParameterName=x\nDataType=0x0007\nAccessType=ro");
  auto w = warnings_of(text);
  EXPECT_NE(w.find("[2100sub1]"), std::string::npos) << w;
  EXPECT_TRUE(Eds::parse(text, "t").problem(0x2100, 1));
  w =
      warnings_of(with("[2100]\nParameterName=R\nObjectType=0x9\nSubNumber=3\n"
                       "[2100sub0]\nParameterName=n\nDataType=0x0005\nAccessType=const"));
  EXPECT_NE(w.find("[2100] SubNumber = '3'"), std::string::npos) << w;
  // A section twice: the first is used, the line named.
  text = with("[6041]\nParameterName=again\nDataType=0x0007\nAccessType=rw");
  w = warnings_of(text);
  EXPECT_NE(w.find("test.eds: line 58: [6041] appears again"), std::string::npos) << w;
  EXPECT_EQ(Eds::parse(text, "t").find(0x6041, 0)->name, "Statusword");
  text = with("[6060]\nParameterName=Mode\nDataType=0x0002\nAccessType=rw\naccesstype=ro");
  w = warnings_of(text);
  EXPECT_NE(w.find("[6060] accesstype = 'ro': expected each key once"), std::string::npos) << w;
  EXPECT_EQ(Eds::parse(text, "t").find(0x6060, 0)->access, EdsAccess::kRw);
  // A list naming an object that has no section.
  w = warnings_of(std::string(kSmall) + "\n[OptionalObjects]\nSupportedObjects=1\n1=0x6502\n");
  EXPECT_NE(w.find("[OptionalObjects] 1 = '0x6502'"), std::string::npos) << w;
  // Not an EDS at all: no object section.
  auto e = error_of("this is not an EDS\n");
  EXPECT_NE(e.find("test.eds"), std::string::npos) << e;
  EXPECT_NE(e.find("no object sections"), std::string::npos) << e;
  e = error_of("[FileInfo]\nFileName=x.eds\n");
  EXPECT_NE(e.find("no object sections"), std::string::npos) << e;
  EXPECT_FALSE(error_of(std::string("[1000]\nParameterName=a\0b", 24)).empty());
}

TEST(EdsHostile, HugeFileIsRefusedBeforeParsing) {
  const auto path = std::filesystem::temp_directory_path() / "wavebench_huge_test.eds";
  {
    std::ofstream out(path, std::ios::binary);
    const std::string line = "; padding padding padding padding padding padding padding\n";
    for (std::size_t n = 0; n <= Eds::kMaxFileBytes / line.size() + 1; ++n) out << line;
  }
  try {
    Eds::load(path);
    ADD_FAILURE() << "a file over the limit was read";
  } catch (const EdsError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    EXPECT_NE(what.find("at most"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
  EXPECT_THROW(Eds::load(path), EdsError);  // gone: unreadable, named
  EXPECT_THROW(Eds::parse(std::string(Eds::kMaxFileBytes + 1, ';')), EdsError);
}

TEST(EdsUsedObjects, DisagreementsAreNamed) {
  const auto eds = Eds::parse(kSmall, "small.eds");
  const UsedObject used[] = {
      {0x6041, 0, "statusword", datatype::kUnsigned16, 0, UsedAccess::kRead, UsedInPdo::kTpdo},
      {0x1000, 0, "device type", datatype::kUnsigned16, 0, UsedAccess::kRead},     // wrong type
      {0x1018, 1, "vendor-ID", datatype::kUnsigned32, 0, UsedAccess::kReadWrite},  // ro
      {0x1018, 0, "count", datatype::kUnsigned8, 0, UsedAccess::kRead, UsedInPdo::kTpdo},
      {0x6081, 0, "profile velocity", datatype::kUnsigned32, 0, UsedAccess::kReadWrite},
      {0x60F4, 0, "following error", datatype::kInteger32, 0, UsedAccess::kRead, UsedInPdo::kTpdo,
       "no following-error channel"},
  };
  const auto problems = check_against_eds(used, eds);
  ASSERT_EQ(problems.size(), 4U);
  EXPECT_NE(problems[0].find("0x1000:0 device type: EDS DataType UNSIGNED32, expected UNSIGNED16"),
            std::string::npos)
      << problems[0];
  EXPECT_NE(problems[1].find("0x1018:1 vendor-ID: EDS AccessType ro"), std::string::npos)
      << problems[1];
  EXPECT_NE(problems[2].find("0x1018:0 count: EDS PDOMapping 0"), std::string::npos) << problems[2];
  EXPECT_NE(problems[3].find("0x6081:0 profile velocity: not in the EDS"), std::string::npos)
      << problems[3];
}

}  // namespace
}  // namespace wavebench::canopen

namespace wavebench::canopen {
namespace {

// A device whose TPDO parameters are read-only (a Faulhaber EDS declares them so, issue 20):
// the bench reads the mapping back and uses it as found, so `ro` / `const` on the objects it
// would write is no problem for them; on any other object it stays one.
TEST(EdsUsedObjects, ReadOnlyTpdoParametersAreAcceptedWhereTheBenchReadsThemBack) {
  const auto eds = Eds::parse(R"([1800]
ParameterName=TPDO1 communication
ObjectType=0x9
SubNumber=3

[1800sub0]
ParameterName=Highest sub-index
DataType=0x0005
AccessType=const
DefaultValue=2

[1800sub1]
ParameterName=COB-ID
DataType=0x0007
AccessType=ro
DefaultValue=$NODEID+0x180

[1800sub2]
ParameterName=Transmission type
DataType=0x0005
AccessType=const
DefaultValue=1

[1A00]
ParameterName=TPDO1 mapping
ObjectType=0x9
SubNumber=2

[1A00sub0]
ParameterName=Number of mapped objects
DataType=0x0005
AccessType=ro
DefaultValue=1

[1A00sub1]
ParameterName=Mapped object 1
DataType=0x0007
AccessType=ro
DefaultValue=0x60640020
)",
                              "fixed.eds");
  const auto node = node_objects();
  std::vector<UsedObject> tpdo;
  for (const auto& u : node)
    if (u.index == 0x1800 || u.index == 0x1A00) tpdo.push_back(u);
  ASSERT_EQ(tpdo.size(), 4U);
  for (const auto& u : tpdo) EXPECT_TRUE(u.may_be_read_only) << describe(u);
  EXPECT_TRUE(check_against_eds(tpdo, eds).empty());
  // Without the flag the same EDS is a problem (an object the bench must write).
  tpdo[0].may_be_read_only = false;
  const auto problems = check_against_eds(tpdo, eds);
  ASSERT_EQ(problems.size(), 1U);
  EXPECT_NE(problems[0].find("0x1800:1 TPDO1 COB-ID: EDS AccessType ro"), std::string::npos)
      << problems[0];
  // The drive's TPDO2 parameters are flagged as well.
  for (const auto& u : Cia402Drive::used_objects()) {
    if ((u.index & 0xFF00) == 0x1800 || (u.index & 0xFF00) == 0x1A00) {
      EXPECT_TRUE(u.may_be_read_only) << describe(u);
    }
  }
}

}  // namespace
}  // namespace wavebench::canopen

namespace wavebench::canopen {
namespace {

// An optional object that the EDS describes otherwise than the bench would use it (a read-only
// 0x1017, a 0x60F4 that cannot be mapped) is one the bench does without: no refusal. The same
// disagreement on a required object stays one.
TEST(EdsUsedObjects, AnOptionalObjectDescribedOtherwiseIsNoProblem) {
  const auto eds = Eds::parse(R"([1017]
ParameterName=Producer heartbeat time
DataType=0x0006
AccessType=ro
DefaultValue=0

[60F4]
ParameterName=Following error actual value
DataType=0x0004
AccessType=ro
PDOMapping=0

[6064]
ParameterName=Position actual value
DataType=0x0004
AccessType=ro
PDOMapping=0
)",
                              "optional.eds");
  const UsedObject used[] = {
      {0x1017, 0, "producer heartbeat time", datatype::kUnsigned16, 0, UsedAccess::kReadWrite,
       UsedInPdo::kNone, "node guarding"},
      {0x60F4, 0, "following error", datatype::kInteger32, 0, UsedAccess::kRead, UsedInPdo::kTpdo,
       "no following-error channel"},
      {0x6064, 0, "position actual value", datatype::kInteger32, 0, UsedAccess::kRead,
       UsedInPdo::kTpdo},
  };
  const auto problems = check_against_eds(used, eds);
  ASSERT_EQ(problems.size(), 1U);
  EXPECT_NE(problems[0].find("0x6064:0 position actual value: EDS PDOMapping 0"), std::string::npos)
      << problems[0];
}

}  // namespace
}  // namespace wavebench::canopen
