// SPDX-License-Identifier: MIT
// `hilbridge profile …` end to end: the real binary on the shipped profiles and the test sets in
// the devices' own formats (a valid set and a set with every kind of problem per device).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cctype>
#include <cstdio>
#include <string>

namespace {

struct Run {
  int status = -1;
  std::string out;
};

Run hilbridge(const std::string& args) {
  const std::string cmd = std::string(HIL_HILBRIDGE) + " " + args + " 2>&1";
  Run r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) r.out += buf.data();
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::string data(const std::string& f) {
  return std::string(HIL_TEST_DATA) + "/" + f;
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST(ProfileCli, ListsAllFiveDevices) {
  const auto r = hilbridge("profile list");
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* d : {"clm14", "sinumerik-elg", "ip247", "wf725-726", "amkasyn-sf"})
    EXPECT_TRUE(contains(r.out, d)) << d;
}

TEST(ProfileCli, ShowOverviewParameterAndErrors) {
  auto r = hilbridge("profile show wf725-726");
  ASSERT_EQ(r.status, 0);
  EXPECT_TRUE(contains(r.out, "MD12 < MD11 < MD13 < MD14"));
  EXPECT_TRUE(contains(r.out, "decisions"));
  r = hilbridge("profile show wf725-726 MD7");
  ASSERT_EQ(r.status, 0);
  EXPECT_TRUE(contains(r.out, "when encoder == 'A_P'"));
  EXPECT_TRUE(contains(r.out, "after_reset"));
  r = hilbridge("profile show clm14 A106");
  EXPECT_TRUE(contains(r.out, "Ax07 <= Ax06"));
  r = hilbridge("profile show clm14 --errors --catalogue serial");
  ASSERT_EQ(r.status, 0);
  EXPECT_TRUE(contains(r.out, "Block # too large"));
  r = hilbridge("profile show ip247 59");
  EXPECT_TRUE(contains(r.out, "Der Referenznocken ist defekt"));
  r = hilbridge("profile show clm14 Z999");
  EXPECT_EQ(r.status, 2);
  r = hilbridge("profile show no-such-device");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.out, "known devices"));
}

TEST(ProfileCli, EncodeAndDecode) {
  auto r = hilbridge("profile encode wf725-726 MD11 -24537");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "BCD    8002 4537"));
  EXPECT_TRUE(contains(r.out, "binary FFFF A027"));
  r = hilbridge("profile decode wf725-726 MD11 \"HEX FFFF A027\"");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "= -24537"));
  r = hilbridge("profile encode wf725-726 MD11 80000000");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "BCD limit"));
  r = hilbridge("profile decode wf725-726 MD11 \"8002 45A7\"");
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(contains(r.out, "not a decimal digit"));
  r = hilbridge("profile encode clm14 A112 \"3000 10\"");
  ASSERT_EQ(r.status, 0);
  EXPECT_TRUE(contains(r.out, "# K A112 03000 10.0$88"));
  r = hilbridge("profile decode clm14 A112 \"03000 10.0\"");
  EXPECT_TRUE(contains(r.out, "= 3000 10"));
  r = hilbridge("profile encode clm14 A125 -00000.000");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(contains(r.out, "# K A125 -00000.000$7B")) << "the manual's telegram keeps the minus: " << r.out;
  r = hilbridge("profile encode clm14 A106 60000");
  EXPECT_EQ(r.status, 1) << "out of range is reported";
  EXPECT_TRUE(contains(r.out, "range 0.1..50000"));
  r = hilbridge("profile encode wf725-726 MD22 1.12 --set control=AK");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.out, "does not exist for this configuration"));
  r = hilbridge("profile encode ip247 fmax 5000");
  EXPECT_TRUE(contains(r.out, "5: KH = 0000\n6: KH = 1388"));
  r = hilbridge("profile encode amkasyn-sf DW6 2 --set sf_type=6");
  EXPECT_TRUE(contains(r.out, "DW6 = 512"));
  r = hilbridge("profile encode sinumerik-elg MD5002 00100010");
  EXPECT_TRUE(contains(r.out, "N5002=00100010"));
  r = hilbridge("profile encode wf725-726 MD1 1 --set bogus=1");
  EXPECT_EQ(r.status, 2);
}

struct SetCase {
  const char* device;
  const char* file;
  const char* extra;
  int status;
  std::vector<std::string> expect;
};

// gtest prints the parameter into the ctest name: the device, file and options, not raw bytes.
void PrintTo(const SetCase& c, std::ostream* os) {
  *os << c.device << ' ' << c.file << (*c.extra ? " " : "") << c.extra;
}

class ValidateSets : public ::testing::TestWithParam<SetCase> {};

TEST_P(ValidateSets, ReportsEveryProblemWithItsLine) {
  const auto& c = GetParam();
  const auto r = hilbridge(std::string("profile validate ") + c.device + " " + data(c.file) + " " + c.extra);
  EXPECT_EQ(r.status, c.status) << r.out;
  for (const auto& e : c.expect) EXPECT_TRUE(contains(r.out, e)) << "missing: " << e << "\n" << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Devices, ValidateSets,
    ::testing::Values(
        SetCase{"clm14", "clm14_manual_defaults.txt", "", 0, {"valid clm14 parameter set (72 parameters)"}},
        SetCase{"clm14",
                "clm14_errors.txt",
                "",
                1,
                {":73: A106 = 60000: rule range 0.1..50000", "possible Vmax", ":75: B010 = 2.2",
                 ":76: A124.homed_output = I1.00.0", ":77: rule checksum 7D: RS Checksum Error (serial error 04)",
                 ":78: X101 = 1", "serial error 11", ":79: A199", "serial error 07", ":80: A112 = 123456 10.0",
                 ":81: A120.track_monitoring = 7", ":83: A109.accel", "A101 (Feed constant) is missing"}},
        SetCase{"wf725-726", "wf725_valid.txt", "", 0, {"valid wf725-726 parameter set (44 parameters)"}},
        SetCase{"wf725-726",
                "wf725_errors.txt",
                "--partial",
                1,
                {":4: MD11 = -24537: rule step resolution", ":5: MD12 = BCD 8004 27A8", "not a decimal digit",
                 ":6: MD12, MD11, MD13, MD14", ":9: MD19, MD20", ":11: MD22 = 12: rule range 0.2..9",
                 ":12: MD34 [MD34=0]", ":13: MD36 = 32800", ":14: MD37 = 1", "does not exist for this configuration",
                 ":15: MD51", "error 121", ":17: MD33, MD25", "11 problem(s)"}},
        SetCase{"wf725-726",
                "wf725_valid.txt",
                "--set module=WF725A",
                1,
                {"MD15", "MD27", "does not exist for this configuration"}},
        SetCase{"ip247", "ip247_manual_md.txt", "", 0, {"valid ip247 parameter set (35 parameters)"}},
        SetCase{
            "ip247",
            "ip247_errors.txt",
            "",
            1,
            {":3: DW1 = 69", ":7: DW5, DW7, DW9", "MD error 6", ":13: DW11 = 40: rule range 1..31", ":14: DW12 = 65",
             ":16: DW14, DW13", "MD error 10", "MD error 7", "MD error 8", "DW 70 is outside", "KY '300,1'"}},
        SetCase{"sinumerik-elg", "elg_valid.tape", "", 0, {"valid sinumerik-elg parameter set (19 parameters)"}},
        SetCase{"sinumerik-elg",
                "elg_errors.tape",
                "",
                1,
                {":2: MD3960 = 2500000: rule range 0..2000000", ":4: MD2120, MD2040", "alarm 112*", ":5: MD2520",
                 "alarm 2200", ":7: MD5002", ":8: MD5020.drive_axis", ":9: MD5022 = 0000010", "alarm 32", ":10: MD9999",
                 "alarm 3018", ":15: R21 = 0", ":16: R40, MD169"}},
        SetCase{"amkasyn-sf",
                "amk_fipw_printing_mark.txt",
                "--set id2_ms=2",
                0,
                {"valid amkasyn-sf parameter set (39 parameters)"}},
        SetCase{"amkasyn-sf", "amk_regl_force.txt", "--set id2_ms=1", 0, {"valid amkasyn-sf parameter set"}},
        SetCase{"amkasyn-sf",
                "amk_errors.txt",
                "--set id2_ms=2",
                1,
                {"Printing mark control only in BA 2 or 98", ":5: INIT_DL2, INIT_DR2", ":8: INIT_DR4",
                 ":12: DR0, INIT_DL0", ":16: DW3, id2_ms", ":18: DW5, DW4", ":21: DW12, DD10", ":22: DW22, DW18, DW23",
                 ":24: DR7", ":25: DW30 = 5", ":26: DD2 = 1", ":27: DW2 = 40000", "12 problem(s)"}}),
    [](const ::testing::TestParamInfo<SetCase>& p) {
      std::string name = p.param.file;
      name = name.substr(0, name.find('.'));
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name + "_" + std::to_string(p.index);
    });

TEST(ProfileCli, ValidateUsageErrors) {
  auto r = hilbridge("profile validate clm14 /nonexistent/set.txt");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(contains(r.out, "cannot read"));
  r = hilbridge("profile validate clm14 " + data("clm14_manual_defaults.txt") + " --set hardware_axes");
  EXPECT_EQ(r.status, 2);
  r = hilbridge("profile");
  EXPECT_NE(r.status, 0);
}
