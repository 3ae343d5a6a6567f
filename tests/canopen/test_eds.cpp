// SPDX-License-Identifier: MIT
// CiA 306 EDS/DCF parser: the shipped CiA 402 drive EDS, $NODEID expressions, CompactSubObj,
// ParameterValue, limits, and errors that name file, line, section and key.
#include <gtest/gtest.h>

#include <limits>

#include "hil/canopen/eds.hpp"

using namespace hil::canopen;

namespace {
const char* k_profile = HIL_CANOPEN_PROFILE_DIR "/hil_cia402_drive.eds";

std::string minimal(std::string_view extra_objects, std::string_view extra_list = "") {
  return std::string("[MandatoryObjects]\nSupportedObjects=1\n1=0x1000\n[OptionalObjects]\n") +
         std::string(extra_list) +
         "\n[1000]\nParameterName=Device type\nObjectType=0x7\nDataType=0x0007\nAccessType = ro "
         "\nDefaultValue=0x192\n" +
         std::string(extra_objects);
}
}  // namespace

TEST(Eds, IntegerExpressions) {
  struct Row {
    const char* text;
    NodeId node;
    std::optional<std::int64_t> value;
  };
  const Row rows[] = {
      {"$NODEID+0x180", 5, 0x185},
      {"0x580+$NODEID", 5, 0x585},
      {"$nodeid + 0x200", 127, 0x27F},
      {"10", 1, 10},
      {"-100", 1, -100},
      {"017", 1, 15},
      {"0", 1, 0},
      {"0x80000000+$NODEID", 3, 0x80000003},
      {"$NODEID-1", 4, 3},
      {"", 1, std::nullopt},
      {"0x", 1, std::nullopt},
      {"12abc", 1, std::nullopt},
      {"$NODEID+", 1, std::nullopt},
      {"08", 1, std::nullopt},
  };
  for (const auto& r : rows) EXPECT_EQ(eval_eds_integer(r.text, r.node), r.value) << r.text;
}

TEST(Eds, ShippedCia402ProfileLoads) {
  auto d = load_eds(k_profile, 5);
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_EQ(d->info.vendor_number, 0xA11u);
  EXPECT_EQ(d->info.product_number, 0x402u);
  const auto& od = d->od;
  EXPECT_EQ(od.get_int(0x1000, 0), 0x00020192);
  EXPECT_EQ(od.get_int(0x1014, 0), 0x85) << "$NODEID+0x80";
  EXPECT_EQ(od.get_int(0x1200, 1), 0x605);
  EXPECT_EQ(od.get_int(0x1800, 1), 0x185);
  EXPECT_EQ(od.get_int(0x1402, 1), 0x80000405) << "RPDO3 starts disabled";
  EXPECT_EQ(od.get_int(0x1A01, 2), 0x60640020);
  EXPECT_EQ(od.get_int(0x1016, 0), 2) << "CompactSubObj sub 0";
  EXPECT_EQ(od.find(0x1016, 2)->name, "Consumer heartbeat time 2");
  EXPECT_EQ(od.get_int(0x607D, 1), -2147483648LL);
  EXPECT_EQ(od.get_int(0x60C2, 2), -3);
  const auto* cw = od.find(0x6040, 0);
  ASSERT_NE(cw, nullptr);
  EXPECT_EQ(cw->access, Access::rww);
  EXPECT_TRUE(cw->pdo_mappable);
  const auto* name = od.find(0x1008, 0);
  EXPECT_EQ(std::string(name->value.begin(), name->value.end()), "hilbridge simulated CiA 402 drive");
  EXPECT_EQ(od.find(0x605A, 0)->high, 8);
  EXPECT_TRUE(d->parameter_values.empty()) << "an EDS has no ParameterValue";
}

TEST(Eds, DcfParameterValueAndNodeId) {
  const auto text = minimal(
      "[1017]\nParameterName=Heartbeat\nObjectType=0x7\nDataType=0x0006\nAccessType=rw\nDefaultValue=0\n"
      "ParameterValue=100\n[DeviceComissioning]\nNodeID=0x0C\n",
      "SupportedObjects=1\n1=0x1017");
  auto d = parse_eds(text, "x.dcf", 0);
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_EQ(d->dcf_node_id, 12);
  ASSERT_EQ(d->parameter_values.size(), 1u);
  EXPECT_EQ(d->parameter_values[0].index, 0x1017);
  EXPECT_EQ(d->parameter_values[0].bytes, (std::vector<std::uint8_t>{100, 0}));
  EXPECT_EQ(d->od.get_int(0x1017, 0), 100);
}

TEST(Eds, CompactSubObjWithNameAndValueSections) {
  const auto text = minimal(
      "[1016]\nParameterName=HB\nObjectType=0x8\nDataType=0x0007\nAccessType=rw\nDefaultValue=0\n"
      "PDOMapping=0\nCompactSubObj=3\n[1016Name]\nNrOfEntries=1\n2=Watch node 9\n"
      "[1016Value]\nNrOfEntries=1\n2=0x00090064\n",
      "SupportedObjects=1\n1=0x1016");
  auto d = parse_eds(text, "c.dcf", 1);
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_EQ(d->od.get_int(0x1016, 0), 3);
  EXPECT_EQ(d->od.find(0x1016, 0)->access, Access::ro);
  EXPECT_EQ(d->od.find(0x1016, 2)->name, "Watch node 9");
  EXPECT_EQ(d->od.get_int(0x1016, 2), 0x00090064);
  EXPECT_EQ(d->od.get_int(0x1016, 3), 0);
  ASSERT_EQ(d->parameter_values.size(), 1u);
  EXPECT_EQ(d->parameter_values[0].sub, 2);
}

TEST(Eds, ErrorsNameFileLineSectionAndKey) {
  struct Row {
    std::string text;
    int line;
    const char* key;
    const char* message_part;
  };
  const Row rows[] = {
      {minimal("[2000]\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\nDefaultValue=256\n",
               "SupportedObjects=1\n1=0x2000"),
       17, "[2000] DefaultValue", "does not fit UNSIGNED8"},
      {minimal("[2000]\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\nParameterValue=$NODE\n",
               "SupportedObjects=1\n1=0x2000"),
       17, "[2000] ParameterValue", "not an integer"},
      {minimal("[2000\n"), 12, "[[2000]", "malformed section header"},
      {minimal("garbage line\n"), 12, "[1000] garbage line", "expected Key=Value"},
      {"Key=1\n[1000]\n", 1, "[] Key", "key outside of any section"},
      {"[FileInfo]\nFileName=x.eds\n", 0, "", "no objects"},
  };
  for (const auto& r : rows) {
    auto d = parse_eds(r.text, "bad.eds", 1);
    ASSERT_FALSE(d) << r.key;
    EXPECT_EQ(d.error().file, "bad.eds");
    EXPECT_EQ(d.error().line, r.line) << r.key;
    EXPECT_EQ(d.error().key, r.key);
    EXPECT_NE(d.error().message.find(r.message_part), std::string::npos) << d.error().message;
  }
  auto missing = load_eds("/nonexistent/x.eds", 1);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("cannot open"), std::string::npos);
}

TEST(Eds, NumbersAreRangeCheckedAndNeverOverflow) {
  // Beyond INT64 or overflowing the sum: not a number, instead of a wrapped one (or UB).
  EXPECT_EQ(eval_eds_integer("0x8000000000000000", 1), std::nullopt);
  EXPECT_EQ(eval_eds_integer("0xFFFFFFFFFFFFFFFF", 1), std::nullopt);
  EXPECT_EQ(eval_eds_integer("-0x8000000000000000", 1), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(eval_eds_integer("0x7FFFFFFFFFFFFFFF+$NODEID", 1), std::nullopt);
  EXPECT_EQ(eval_eds_integer("-0x8000000000000000-1", 1), std::nullopt);
  EXPECT_EQ(eval_eds_integer("0-(0x8000000000000000)", 1), std::nullopt);

  // Identity numbers are UNSIGNED32 (0x1018): 0x100000A11 is not 0xA11.
  auto vendor = parse_eds("[DeviceInfo]\nVendorNumber=0x100000A11\n" + minimal(""), "v.eds", 1);
  ASSERT_FALSE(vendor);
  EXPECT_EQ(vendor.error().key, "[DeviceInfo] VendorNumber");
  EXPECT_NE(vendor.error().message.find("0..0xFFFFFFFF"), std::string::npos) << vendor.error().message;
  auto negative = parse_eds("[DeviceInfo]\nProductNumber=-1\n" + minimal(""), "v.eds", 1);
  ASSERT_FALSE(negative);
  EXPECT_EQ(negative.error().key, "[DeviceInfo] ProductNumber");

  // A negative count must not drop the listed (mandatory) objects: the entries present are used,
  // with a warning (issue 13: lenient and loud).
  auto count = parse_eds(minimal("", "SupportedObjects=-5\n"), "c.eds", 1);
  ASSERT_TRUE(count) << count.error().describe();
  bool warned = false;
  for (const auto& w : count->warnings) warned = warned || w.key.find("SupportedObjects") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(Eds, AUtf8ByteOrderMarkIsAccepted) {
  auto d = parse_eds("\xEF\xBB\xBF" + minimal(""), "bom.eds", 1);
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_NE(d->od.find(0x1000, 0), nullptr);
}

// What python-canopen and the CANopen editors accept is accepted, each oddity a warning that
// names file, line and key.
TEST(Eds, LenientWithAWarningPerOddity) {
  struct Row {
    std::string text;
    int line;
    const char* key;
    const char* message_part;
  };
  const Row rows[] = {
      {minimal("[2000]\nObjectType=0x7\nDataType=0x0099\nAccessType=rw\n", "SupportedObjects=1\n1=0x2000"), 15,
       "[2000] DataType", "unsupported data type 0x0099: 0x2000:0 skipped"},
      {minimal("[2000]\nObjectType=0x7\nDataType=0x0005\nAccessType=rx\n", "SupportedObjects=1\n1=0x2000"), 16,
       "[2000] AccessType", "'rx'"},
      {minimal("[2000]\nObjectType=0x7\nDataType=0x0005\nAccessType=rw\nDefaultValue=$NODE\n",
               "SupportedObjects=1\n1=0x2000"),
       17, "[2000] DefaultValue", "the default is 0"},
      {minimal("", "SupportedObjects=1\n1=0x2000"), 6, "[OptionalObjects] 1", "no [2000] section: ignored"},
      {minimal("[2000]\nParameterName=A\nObjectType=0x9\nSubNumber=2\n[2000sub0]\nDataType=0x0005\nAccessType=ro\n",
               "SupportedObjects=1\n1=0x2000"),
       16, "[2000] SubNumber", "says 2 sub-objects but 1"},
      {minimal("[2001]\nParameterName=Unlisted\nDataType=0x0006\nAccessType=rw\n"), 12, "[2001]",
       "not in [MandatoryObjects]"},
      {minimal("[2000]\nParameterName=A\nDataType=0x0006\n", "SupportedObjects=1\n1=0x2000"), 13, "[2000] AccessType",
       "taken as rw"},
      {minimal("[2000]\nDataType=0x0006\nAccessType=rw\n", "SupportedObjects=1\n1=0x2000"), 13, "[2000] ParameterName",
       "named '0x2000:0'"},
      {minimal("[2000]\nParameterName=A\nDataType=0x0006\nAccessType=rw\n[2000]\nDefaultValue=3\n",
               "SupportedObjects=1\n1=0x2000"),
       17, "[2000]", "section appears again"},
      {minimal("[VendorModuleXYZ]\nFoo=1\n"), 12, "[VendorModuleXYZ]", "unknown section"},
      {minimal("", "SupportedObjects=3\n1=0x1000"), 5, "[OptionalObjects] SupportedObjects", "says '3' but 1"},
      {minimal("[2000sub1]\nDataType=0x0005\n"), 12, "[2000sub1]", "which has no [2000] section"},
  };
  for (const auto& r : rows) {
    auto d = parse_eds(r.text, "odd.eds", 1);
    ASSERT_TRUE(d) << r.key << ": " << d.error().describe();
    bool found = false;
    for (const auto& w : d->warnings)
      if (w.key == r.key && w.line == r.line && w.message.find(r.message_part) != std::string::npos) found = true;
    std::string all;
    for (const auto& w : d->warnings) all += w.describe() + "\n";
    EXPECT_TRUE(found) << r.key << " line " << r.line << " '" << r.message_part << "' not among:\n" << all;
    for (const auto& w : d->warnings) EXPECT_EQ(w.file, "odd.eds");
  }
}

TEST(Eds, MixedCaseKeysCommentsAndNodeIdExpressionsReadLikePythonCanopen) {
  const std::string text =
      "\xEF\xBB\xBF; vendor tool export\r\n[DeviceInfo]\r\nvendorNumber = 0x0000029C ; vendor\r\n"
      "PRODUCTNUMBER=0x10\r\n\r\n[MandatoryObjects]\r\nSupportedObjects=1\r\n1=0x1000\r\n"
      "[1000]\r\nparametername=Device type\r\nObjectType=7\r\nDATATYPE=0x0007\r\naccesstype=RO\r\n"
      "DefaultValue=0x00020192\r\n[1800]\r\nParameter Name=TPDO1\r\nObjectType=9\r\nSubNumber=2\r\n"
      "[1800sub0]\r\nParameterName=n\r\nDataType=5\r\nAccessType=ro\r\nDefaultValue=2\r\n[1800sub1]\r\n"
      "ParameterName=COB-ID\r\nDataType=7\r\nAccessType=rw\r\nDefaultValue=$NODEID+0x180\r\n";
  auto d = parse_eds(text, "vendor.eds", 9);
  ASSERT_TRUE(d) << d.error().describe();
  EXPECT_EQ(d->info.vendor_number, 0x29Cu);
  EXPECT_EQ(d->info.product_number, 0x10u);
  EXPECT_EQ(d->od.get_int(0x1000, 0), 0x00020192);
  EXPECT_EQ(d->od.find(0x1000, 0)->access, Access::ro);
  EXPECT_EQ(d->od.get_int(0x1800, 1), 0x189);
  std::string all;
  for (const auto& w : d->warnings) all += w.describe() + "\n";
  EXPECT_NE(all.find("byte-order mark"), std::string::npos) << all;
  EXPECT_NE(all.find("inline ';' comment"), std::string::npos) << all;
  EXPECT_NE(all.find("not spelled as CiA 306 writes them"), std::string::npos) << all;
  EXPECT_NE(all.find("object 0x1800 is not in"), std::string::npos) << all;
}
