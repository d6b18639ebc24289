// The forms CiA 306 allows and vendors' tools write, one small file each (written here from
// CiA 306, not copied from any vendor's file): object types, CompactSubObj, data types and
// their values, encodings, line ends, comments, case, DCF values, and the inconsistencies that
// warn instead of refusing the file.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "wavebench/canopen/eds.hpp"
#include "wavebench/canopen/used_object.hpp"

namespace wavebench::canopen {
namespace {

// The objects every form below is added to: device type and an identity record.
const std::string kBase =
    "[FileInfo]\nFileName=forms.eds\n\n"
    "[DeviceInfo]\nVendorName=Forms GmbH\nVendorNumber=0x12345678\nProductName=Form drive\n"
    "ProductNumber=42\nRevisionNumber=0x00010002\n\n"
    "[MandatoryObjects]\nSupportedObjects=2\n1=0x1000\n2=0x1018\n\n"
    "[1000]\nParameterName=Device type\nObjectType=0x7\nDataType=0x0007\nAccessType=ro\n"
    "DefaultValue=0x00020192\nPDOMapping=0\n\n"
    "[1018]\nParameterName=Identity\nObjectType=0x9\nSubNumber=2\n\n"
    "[1018sub0]\nParameterName=Highest sub-index\nObjectType=0x7\nDataType=0x0005\n"
    "AccessType=ro\nDefaultValue=1\n\n"
    "[1018sub1]\nParameterName=Vendor-ID\nObjectType=0x7\nDataType=0x0007\nAccessType=ro\n"
    "DefaultValue=0x12345678\n\n";

Eds read(const std::string& more) {
  return Eds::parse(kBase + more, "forms.eds");
}

std::string joined(const Eds& eds) {
  std::string out;
  for (const auto& w : eds.warnings()) out += w + "\n";
  return out;
}

TEST(EdsForms, BaseReadsWithoutWarnings) {
  const auto eds = read("");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_EQ(eds.vendor_number(), 0x12345678U);
  EXPECT_EQ(eds.product_number(), 42U);
  EXPECT_EQ(eds.revision_number(), 0x00010002U);
  EXPECT_EQ(eds.vendor_name(), "Forms GmbH");
  EXPECT_EQ(eds.product_name(), "Form drive");
  EXPECT_FALSE(eds.commissioning().node_id);
}

TEST(EdsForms, DomainObjectWithEmptyAndNullDefaults) {
  const auto eds = read(
      "[1F50]\nParameterName=Program data\nObjectType=0x2\nDataType=0x000F\nAccessType=wo\n"
      "DefaultValue=\n\n"
      "[2F00]\nParameterName=Vendor blob\nObjectType=0x2\nDataType=0x000F\nAccessType=rw\n"
      "DefaultValue=NULL\n\n"
      "[2F01]\nParameterName=Bare domain\nObjectType=0x02\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  const auto* program = eds.find(0x1F50, 0);
  ASSERT_NE(program, nullptr);
  EXPECT_EQ(program->object_type, kObjectDomain);
  EXPECT_EQ(program->data_type, datatype::kDomain);
  EXPECT_EQ(program->access, EdsAccess::kWo);
  EXPECT_EQ(program->default_value, "");
  const auto* blob = eds.find(0x2F00, 0);
  ASSERT_NE(blob, nullptr);
  EXPECT_EQ(blob->default_value, "NULL");
  EXPECT_FALSE(eds.default_integer(*blob));
  // CiA 306: a DOMAIN's DataType and AccessType may be left out (DOMAIN, rw).
  const auto* bare = eds.find(0x2F01, 0);
  ASSERT_NE(bare, nullptr);
  EXPECT_EQ(bare->data_type, datatype::kDomain);
  EXPECT_EQ(bare->access, EdsAccess::kRw);
}

TEST(EdsForms, DeftypeAndDefstructSections) {
  const auto eds = read(
      "[0007]\nParameterName=UNSIGNED32\nObjectType=0x5\nDataType=0x0007\nAccessType=ro\n"
      "DefaultValue=32\n\n"
      "[0040]\nParameterName=Vendor struct\nObjectType=0x6\nSubNumber=3\n\n"
      "[0040sub0]\nParameterName=Highest sub-index\nDataType=0x0005\nAccessType=const\n"
      "DefaultValue=2\n\n"
      "[0040sub1]\nParameterName=Field "
      "1\nDataType=0x0005\nAccessType=const\nDefaultValue=0x0006\n\n"
      "[0040sub2]\nParameterName=Field "
      "2\nDataType=0x0005\nAccessType=const\nDefaultValue=0x0007\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  ASSERT_NE(eds.find(0x0007, 0), nullptr);
  EXPECT_EQ(eds.find(0x0007, 0)->object_type, kObjectDeftype);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x0007, 0)), 32);
  ASSERT_NE(eds.find(0x0040, 2), nullptr);
  EXPECT_EQ(eds.find(0x0040, 2)->object_type, kObjectDefstruct);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x0040, 2)), 7);
}

TEST(EdsForms, StringDefaultsKeepSpacesEqualsAndSemicolons) {
  const auto eds = read(
      "[1008]\nParameterName=Manufacturer device name\nDataType=0x0009\nAccessType=const\n"
      "DefaultValue=Drive  X=1; rev B \n\n"
      "[2010]\nParameterName=Serial bytes\nDataType=0x000A\nAccessType=ro\n"
      "DefaultValue=01 02 A0 FF\n\n"
      "[2011]\nParameterName=Unicode label\nDataType=0x000B\nAccessType=ro\nDefaultValue=abc\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_EQ(eds.find(0x1008, 0)->default_value, "Drive  X=1; rev B");  // trimmed at the ends
  EXPECT_FALSE(eds.default_integer(*eds.find(0x1008, 0)));
  EXPECT_EQ(eds.find(0x2010, 0)->default_value, "01 02 A0 FF");
  EXPECT_EQ(eds.find(0x2011, 0)->data_type, datatype::kUnicodeString);
}

TEST(EdsForms, SixtyFourBitExtremes) {
  const auto eds = read(
      "[2020]\nParameterName=u64 max\nDataType=0x001B\nAccessType=ro\n"
      "DefaultValue=0xFFFFFFFFFFFFFFFF\nHighLimit=18446744073709551615\n\n"
      "[2021]\nParameterName=i64 min\nDataType=0x0015\nAccessType=ro\n"
      "DefaultValue=-9223372036854775808\nLowLimit=-0x8000000000000000\n\n"
      "[2022]\nParameterName=u64 over\nDataType=0x001B\nAccessType=ro\n"
      "DefaultValue=0x1FFFFFFFFFFFFFFFF\n");
  const auto w = joined(eds);
  // Only the value past UINT64_MAX warns.
  ASSERT_EQ(eds.warnings().size(), 1U) << w;
  EXPECT_NE(w.find("[2022] DefaultValue = '0x1FFFFFFFFFFFFFFFF'"), std::string::npos) << w;
  const auto* max = eds.find(0x2020, 0);
  ASSERT_NE(max, nullptr);
  EXPECT_EQ(*eds.default_unsigned(*max), std::numeric_limits<std::uint64_t>::max());
  EXPECT_FALSE(eds.default_integer(*max));  // beyond int64: default_unsigned has it
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2021, 0)), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(parse_eds_unsigned("0xFFFFFFFFFFFFFFFF"), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(parse_eds_integer("-9223372036854775808"), std::numeric_limits<std::int64_t>::min());
  EXPECT_THROW(parse_eds_integer("0xFFFFFFFFFFFFFFFF"), std::invalid_argument);
  EXPECT_THROW(parse_eds_unsigned("-1"), std::invalid_argument);
  EXPECT_THROW(parse_eds_unsigned("$NODEID+0xFFFFFFFFFFFFFFFF", 1), std::invalid_argument);
}

TEST(EdsForms, OddWidthsTimesAndReals) {
  const auto eds = read(
      "[2030]\nParameterName=i24\nDataType=0x0010\nAccessType=rw\nDefaultValue=-8388608\n\n"
      "[2031]\nParameterName=u24\nDataType=0x0016\nAccessType=rw\nDefaultValue=0xFFFFFF\n\n"
      "[2032]\nParameterName=u40\nDataType=0x0018\nAccessType=rw\nDefaultValue=0xFFFFFFFFFF\n\n"
      "[2033]\nParameterName=i56\nDataType=0x0014\nAccessType=rw\nDefaultValue=0xFFFFFFFFFFFFFF\n\n"
      "[2034]\nParameterName=time\nDataType=0x000C\nAccessType=rw\nDefaultValue=0\n\n"
      "[2035]\nParameterName=diff\nDataType=0x000D\nAccessType=rw\nDefaultValue=1000 2\n\n"
      "[2036]\nParameterName=gain\nDataType=0x0008\nAccessType=rw\nDefaultValue=1.5E-3\n\n"
      "[2037]\nParameterName=gain64\nDataType=0x0011\nAccessType=rw\nDefaultValue=-2.25\n\n"
      "[2038]\nParameterName=i16 pattern\nDataType=0x0003\nAccessType=rw\nDefaultValue=0xFFFF\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2030, 0)), -8388608);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2031, 0)), 0xFFFFFF);
  EXPECT_EQ(*eds.default_unsigned(*eds.find(0x2032, 0)), 0xFFFFFFFFFFULL);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2033, 0)), -1);  // a signed bit pattern
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2038, 0)), -1);
  EXPECT_EQ(data_type_size(datatype::kInteger24), 3U);
  EXPECT_EQ(data_type_size(datatype::kUnsigned56), 7U);
  EXPECT_EQ(data_type_name(datatype::kUnsigned40), "UNSIGNED40");
  EXPECT_FALSE(eds.default_integer(*eds.find(0x2034, 0)));  // not an integer type
  EXPECT_EQ(eds.find(0x2035, 0)->default_value, "1000 2");
  EXPECT_FALSE(eds.default_integer(*eds.find(0x2036, 0)));
  const auto w =
      joined(read("[2039]\nParameterName=u24\nDataType=0x0016\nAccessType=rw\n"
                  "DefaultValue=0x1000000\n"));
  EXPECT_NE(w.find("expected UNSIGNED24 in 0..16777215"), std::string::npos) << w;
}

TEST(EdsForms, NodeIdFormsOctalAndNegative) {
  const auto eds = read(
      "[1800]\nParameterName=TPDO1\nObjectType=0x9\nSubNumber=4\n\n"
      "[1800sub0]\nParameterName=n\nDataType=0x0005\nAccessType=ro\nDefaultValue=3\n\n"
      "[1800sub1]\nParameterName=COB-ID\nDataType=0x0007\nAccessType=rw\n"
      "DefaultValue=$NODEID+0x180\n\n"
      "[1800sub2]\nParameterName=COB-ID after\nDataType=0x0007\nAccessType=rw\n"
      "DefaultValue=0x180+$NODEID\n\n"
      "[1800sub3]\nParameterName=lower case\nDataType=0x0007\nAccessType=rw\n"
      "DefaultValue=$nodeid+0x200\n\n"
      "[2040]\nParameterName=octal\nDataType=0x0006\nAccessType=rw\nDefaultValue=010\n\n"
      "[2041]\nParameterName=negative\nDataType=0x0004\nAccessType=rw\nDefaultValue=-0x10\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x1800, 1), 5), 0x185);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x1800, 2), 5), 0x185);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x1800, 3), 127), 0x27F);
  EXPECT_EQ(*eds.default_unsigned(*eds.find(0x1800, 3), 1), 0x201U);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2040, 0)), 8);
  EXPECT_EQ(*eds.default_integer(*eds.find(0x2041, 0)), -16);
}

TEST(EdsForms, EmptyValuesAreNotGiven) {
  const auto eds = Eds::parse(
      "[DeviceInfo]\nVendorName=\nVendorNumber=\nProductNumber= \nRevisionNumber=0x2\n\n"
      "[1000]\nParameterName=Device type\nDataType=0x0007\nAccessType=ro\nDefaultValue=\n"
      "LowLimit=\nHighLimit=\nPDOMapping=\n",
      "empty.eds");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_FALSE(eds.vendor_number());
  EXPECT_FALSE(eds.product_number());
  EXPECT_EQ(eds.revision_number(), 2U);
  EXPECT_EQ(eds.vendor_name(), "");
  const auto* o = eds.find(0x1000, 0);
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(o->default_value, "");
  EXPECT_FALSE(o->low_limit);
  EXPECT_FALSE(o->high_limit);
  EXPECT_FALSE(o->pdo_mapping);
}

TEST(EdsForms, Utf8ByteOrderMarkCrlfCommentsAndLatin1) {
  // A BOM, CRLF line ends, ';' and '#' comments, whitespace around '=', and a Latin-1 0xB5
  // (micro sign) in a name, as Windows tools write them.
  std::string text = "\xEF\xBB\xBF; written by a Windows tool\r\n# another comment\r\n" + kBase;
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const auto bom = Eds::parse(crlf +
                                  "[2050]\r\nParameterName = Torque\r\n DataType = 0x0004 "
                                  "\r\nAccessType=ro\r\n",
                              "bom.eds");
  EXPECT_TRUE(bom.warnings().empty()) << joined(bom);
  ASSERT_NE(bom.find(0x2050, 0), nullptr);
  EXPECT_EQ(bom.find(0x2050, 0)->name, "Torque");
  EXPECT_EQ(bom.find(0x2050, 0)->data_type, datatype::kInteger32);
  EXPECT_EQ(bom.vendor_number(), 0x12345678U);

  const auto latin1 = read(
      "[2051]\nParameterName=Current in \xB5"
      "A\nDataType=0x0004\nAccessType=ro\n");
  EXPECT_TRUE(latin1.warnings().empty()) << joined(latin1);
  ASSERT_NE(latin1.find(0x2051, 0), nullptr);
  EXPECT_EQ(latin1.find(0x2051, 0)->name,
            "Current in \xC2\xB5"
            "A");  // UTF-8 now
  // UTF-8 text stays as it is.
  const auto utf8 = read(
      "[2052]\nParameterName=Current in \xC2\xB5"
      "A\nDataType=0x0004\nAccessType=ro\n");
  EXPECT_EQ(utf8.find(0x2052, 0)->name,
            "Current in \xC2\xB5"
            "A");
}

TEST(EdsForms, KeysAndSectionsInAnyCase) {
  const auto eds = Eds::parse(
      "[DEVICEINFO]\nvendornumber=7\n\n"
      "[1018]\nPARAMETERNAME=Identity\nobjecttype=0x9\nsubnumber=3\n\n"
      "[1018SUB0]\nparametername=n\ndatatype=0x0005\naccesstype=RO\ndefaultvalue=2\n\n"
      "[1018sub1]\nParameterName=Vendor-ID\nDataType=0x0007\nAccessType=Ro\n\n"
      "[1018Sub2]\nParameterName=Product\nDataType=0x0007\nAccessType=CONST\n\n"
      "[6041]\nparametername=Statusword\nDATATYPE=0x0006\nAccessType=ro\npdomapping=1\n",
      "case.eds");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_EQ(eds.vendor_number(), 7U);
  ASSERT_NE(eds.find(0x1018, 0), nullptr);
  ASSERT_NE(eds.find(0x1018, 1), nullptr);
  ASSERT_NE(eds.find(0x1018, 2), nullptr);
  EXPECT_EQ(eds.find(0x1018, 2)->access, EdsAccess::kConst);
  EXPECT_TRUE(eds.find(0x6041, 0)->pdo_mapping);
}

TEST(EdsForms, CompactSubObjZeroIsNotCompact) {
  const auto eds = read(
      "[1016]\nParameterName=Consumer heartbeat time\nObjectType=0x8\nCompactSubObj=0\n"
      "SubNumber=2\n\n"
      "[1016sub0]\nParameterName=n\nDataType=0x0005\nAccessType=ro\nDefaultValue=1\n\n"
      "[1016sub1]\nParameterName=Consumer 1\nDataType=0x0007\nAccessType=rw\nDefaultValue=0\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  ASSERT_NE(eds.find(0x1016, 1), nullptr);
  EXPECT_EQ(eds.find(0x1016, 1)->name, "Consumer 1");
  EXPECT_EQ(eds.find(0x1016, 2), nullptr);
}

TEST(EdsForms, CompactSubObjExpandsWithNames) {
  const auto eds = read(
      "[1003]\nParameterName=Pre-defined error field\nObjectType=0x8\nDataType=0x0007\n"
      "AccessType=ro\nPDOMapping=0\nCompactSubObj=3\nDefaultValue=0\n\n"
      "[1003Name]\nNrOfEntries=2\n1=Newest error\n3=Oldest error\n\n"
      "[2060]\nParameterName=Gain\nObjectType=0x8\nDataType=0x0006\nAccessType=rw\n"
      "PDOMapping=1\nCompactSubObj=2\n\n"
      "[2060Value]\nNrOfEntries=1\n2=0x10\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  const auto* n = eds.find(0x1003, 0);
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->name, "NrOfObjects");
  EXPECT_EQ(n->data_type, datatype::kUnsigned8);
  EXPECT_EQ(n->access, EdsAccess::kRo);
  EXPECT_EQ(*eds.default_integer(*n), 3);
  ASSERT_NE(eds.find(0x1003, 3), nullptr);
  EXPECT_EQ(eds.find(0x4003, 0), nullptr);
  EXPECT_EQ(eds.find(0x1003, 1)->name, "Newest error");
  EXPECT_EQ(eds.find(0x1003, 2)->name, "Pre-defined error field2");  // no name given
  EXPECT_EQ(eds.find(0x1003, 3)->name, "Oldest error");
  EXPECT_EQ(eds.find(0x1003, 3)->data_type, datatype::kUnsigned32);
  EXPECT_EQ(eds.find(0x1003, 3)->object_type, kObjectArray);
  EXPECT_EQ(eds.find(0x1003, 4), nullptr);
  EXPECT_EQ(eds.find(0x2060, 1)->name, "Gain1");
  EXPECT_TRUE(eds.find(0x2060, 2)->pdo_mapping);
  EXPECT_FALSE(eds.find(0x2060, 1)->parameter_value);
  EXPECT_EQ(eds.find(0x2060, 2)->parameter_value.value_or(""), "0x10");
}

TEST(EdsForms, DummyUsageIsOrdinary) {
  const auto eds = read(
      "[DummyUsage]\nDummy0001=0\nDummy0002=1\nDummy0003=1\nDummy0004=1\nDummy0005=1\n"
      "Dummy0006=0\nDummy0007=0\n\n[Comments]\nLines=1\nLine1=a comment section\n\n"
      "[VendorToolSection]\nAnything=goes here\n");
  EXPECT_TRUE(eds.warnings().empty()) << joined(eds);
  EXPECT_NE(eds.find(0x1000, 0), nullptr);
}

TEST(EdsForms, DcfParameterValueAndCommissioning) {
  const auto dcf = read(
      "[DeviceComissioning]\nNodeID=0x05\nNodeName=axis 1\nBaudrate=500\nNetNumber=1\n"
      "LSS_SerialNumber=1234\n\n"
      "[1017]\nParameterName=Producer heartbeat time\nDataType=0x0006\nAccessType=rw\n"
      "DefaultValue=0\nParameterValue=100\nDenotation=heartbeat\n\n"
      "[1014]\nParameterName=COB-ID EMCY\nDataType=0x0007\nAccessType=rw\n"
      "DefaultValue=$NODEID+0x80\nParameterValue=$NODEID+0x80\n");
  EXPECT_TRUE(dcf.warnings().empty()) << joined(dcf);
  EXPECT_EQ(dcf.commissioning().node_id, 5);
  EXPECT_EQ(dcf.commissioning().baudrate_kbit, 500U);
  EXPECT_EQ(dcf.commissioning().node_name, "axis 1");
  const auto* hb = dcf.find(0x1017, 0);
  ASSERT_NE(hb, nullptr);
  EXPECT_EQ(hb->default_value, "0");
  EXPECT_EQ(hb->parameter_value.value_or(""), "100");
  EXPECT_EQ(parse_eds_integer(*dcf.find(0x1014, 0)->parameter_value, 5), 0x85);
  // A malformed configured value warns and is dropped.
  const auto bad = read(
      "[DeviceComissioning]\nNodeID=200\n\n[1017]\nParameterName=hb\n"
      "DataType=0x0006\nAccessType=rw\nParameterValue=fast\n");
  const auto w = joined(bad);
  EXPECT_NE(w.find("[DeviceComissioning] NodeID = '200'"), std::string::npos) << w;
  EXPECT_NE(w.find("[1017] ParameterValue = 'fast'"), std::string::npos) << w;
  EXPECT_FALSE(bad.find(0x1017, 0)->parameter_value);
  EXPECT_FALSE(bad.commissioning().node_id);
}

TEST(EdsForms, SubNumberMismatchWarnsAndTheRestIsUsed) {
  const auto eds = read(
      "[1A00]\nParameterName=TPDO1 mapping\nObjectType=0x9\nSubNumber=9\n\n"
      "[1A00sub0]\nParameterName=n\nDataType=0x0005\nAccessType=rw\nDefaultValue=1\n\n"
      "[1A00sub1]\nParameterName=Mapped 1\nDataType=0x0007\nAccessType=rw\n"
      "DefaultValue=0x60410010\n\n"
      "[6041]\nParameterName=Statusword\nDataType=0x0006\nAccessType=ro\nPDOMapping=1\n");
  ASSERT_EQ(eds.warnings().size(), 1U) << joined(eds);
  const auto& w = eds.warnings().front();
  EXPECT_NE(w.find("forms.eds"), std::string::npos) << w;
  EXPECT_NE(w.find("[1A00] SubNumber = '9'"), std::string::npos) << w;
  EXPECT_NE(w.find("the number of [1A00subN] sections, 2"), std::string::npos) << w;
  EXPECT_NE(eds.find(0x1A00, 1), nullptr);  // the record's own subs still read
  EXPECT_NE(eds.find(0x6041, 0), nullptr);  // and an unrelated object
}

TEST(EdsForms, ListEntryWithoutSectionWarnsAndTheRestIsUsed) {
  const auto eds = read(
      "[OptionalObjects]\nSupportedObjects=2\n1=0x6041\n2=0x6502\n\n"
      "[6041]\nParameterName=Statusword\nDataType=0x0006\nAccessType=ro\nPDOMapping=1\n");
  ASSERT_EQ(eds.warnings().size(), 1U) << joined(eds);
  const auto& w = eds.warnings().front();
  EXPECT_NE(w.find("[OptionalObjects] 2 = '0x6502'"), std::string::npos) << w;
  EXPECT_NE(w.find("[6502] is missing"), std::string::npos) << w;
  EXPECT_NE(eds.find(0x6041, 0), nullptr);
}

TEST(EdsForms, UnreadableUsedObjectSaysWhyInTheCheck) {
  const auto eds = read(
      "[6041]\nParameterName=Statusword\nDataType=0x0006\nAccessType=read-only\nPDOMapping=1\n");
  EXPECT_EQ(eds.find(0x6041, 0), nullptr);
  const UsedObject used[] = {
      {0x6041, 0, "statusword", datatype::kUnsigned16, 0, UsedAccess::kRead, UsedInPdo::kTpdo}};
  const auto problems = check_against_eds(used, eds);
  ASSERT_EQ(problems.size(), 1U);
  EXPECT_NE(problems[0].find("0x6041:0 statusword: in the EDS but unreadable: EDS forms.eds: "
                             "[6041] AccessType = 'read-only'"),
            std::string::npos)
      << problems[0];
}

TEST(EdsForms, UnknownObjectTypeCostsItsSubsToo) {
  const auto eds = read(
      "[2070]\nParameterName=odd\nObjectType=0x3\nSubNumber=2\n\n"
      "[2070sub0]\nParameterName=n\nDataType=0x0005\nAccessType=ro\n\n"
      "[2070sub1]\nParameterName=x\nDataType=0x0005\nAccessType=ro\n");
  ASSERT_EQ(eds.warnings().size(), 1U) << joined(eds);
  EXPECT_NE(eds.warnings()[0].find("[2070] ObjectType = '0x3'"), std::string::npos);
  EXPECT_FALSE(eds.has_index(0x2070));
  ASSERT_TRUE(eds.problem(0x2070, 1));
  EXPECT_NE(eds.problem(0x2070, 1)->find("ObjectType"), std::string::npos);
}

TEST(EdsFormsHostile, AbsurdLineLengthNulAndEndlessWarningsAreBounded) {
  auto refused = [](const std::string& text) {
    try {
      Eds::parse(text, "hostile.eds");
    } catch (const EdsError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto e = refused(kBase + "[2080]\nParameterName=" + std::string(Eds::kMaxLineBytes, 'x') + "\n");
  EXPECT_NE(e.find("hostile.eds: line"), std::string::npos) << e;
  EXPECT_NE(e.find("at most"), std::string::npos) << e;
  e = refused(kBase + std::string("[2080]\nParameterName=a\0b\n", 25));
  EXPECT_NE(e.find("NUL"), std::string::npos) << e;
  // Many malformed lines: the warnings stop at the bound and say how many more there were.
  std::string noise;
  for (std::size_t i = 0; i < Eds::kMaxWarnings + 50; ++i) noise += "not a key\n";
  const auto eds = Eds::parse(kBase + noise, "noise.eds");
  ASSERT_EQ(eds.warnings().size(), Eds::kMaxWarnings + 1);
  EXPECT_NE(eds.warnings().back().find("50 more warnings not listed"), std::string::npos)
      << eds.warnings().back();
  // A long value in a warning is cut at a character boundary, so the message stays UTF-8.
  const auto cut = Eds::parse(kBase +
                                  "[2081]\nParameterName=x\nDataType=0x0005\nAccessType=ro\n"
                                  "DefaultValue=" +
                                  std::string(79, 'a') + "\xC2\xB5\n",
                              "cut.eds");
  ASSERT_EQ(cut.warnings().size(), 1U);
  EXPECT_NE(cut.warnings()[0].find(std::string(79, 'a') + "...'"), std::string::npos)
      << cut.warnings()[0];
}

}  // namespace
}  // namespace wavebench::canopen
