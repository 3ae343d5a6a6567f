// SPDX-License-Identifier: MIT
// IP247 data jobs (manual §4.3.11-4.3.23, §6.3.8; digest ip247.md §4.4, §4.12, §5.5): MD write,
// read, overview, directory and delete; faulty MD kept with its MD error; VP write/read/delete with
// the manual's VP DB image, syntax errors with the module's numbers, the VP directory split over
// DBx/DBx+1 (both manual examples), actual values binary/BCD, SYS-ID write/read, wrong tiles (46),
// interface errors (MB250), memory gaps (61), teach-in (22). Every word is checked exactly.
#include <gtest/gtest.h>

#include <string>

#include "hil/controllers/s5/ip247_data_job.hpp"
#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_module.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

using namespace hil::controllers::s5;
using hil::stepdir::Ip247Error;
using IfE = Ip247InterfaceError;
using W = std::vector<std::uint16_t>;

namespace {

constexpr int data_tile = 3;  // base tile 0: axes 1..3 = SSNR 0..2, data channel = 3

Ip247MachineData manual_md(int db = 10, int axis = 1) {
  Ip247MachineData md;  // the manual's example set (§6.3.8.1)
  md.db = static_cast<std::uint8_t>(db);
  md.axis = axis;
  return md;
}

Ip247DataJob job(int ba, int tile, int q_db, int q_start, int z_db, int z_start, bool bcd = false) {
  return Ip247DataJob{ba, bcd, q_db, q_start, z_db, z_start, tile};
}

Ip247DataResult ok(int words) {
  return {IfE::none, Ip247Error::none, words, 0};
}
Ip247DataResult module_error(Ip247Error e) {
  return {IfE::module, e, 0, 0};
}
Ip247DataResult interface_error(IfE e) {
  return {e, Ip247Error::none, 0, 0};
}

/// The VP DB image of §6.3.8.2 (digest §5.5 b), program 1, 25 words.
const W manual_vp{25,     0x0044, 0x4201, 0,      0,      0x2520, 0x2031, 0x2042, 0x4549,
                  0x5350, 0x4945, 0x4C0A, 0x4E31, 0x2058, 0x3130, 0x3020, 0x4631, 0x3030,
                  0x3020, 0x4D31, 0x300A, 0x4E32, 0x204D, 0x3032, 0x0A00};

W vp_image(int number, const std::string& text) {
  return make_ip247_vp_db(Ip247VpImage{static_cast<std::uint8_t>(number), text, 0, 0}).value();
}

}  // namespace

TEST(Ip247Data, MachineDataWriteReadOverviewDirectoryDelete) {
  Ip247Module m;
  S5Blocks plc{{104, make_ip247_md_db(manual_md())}, {204, W(70, 0xFFFF)}, {205, W(6, 0xFFFF)}, {206, W(15, 0)}};
  // BA20 on the tile of axis 1: AG DB104 -> MD DB10 (the manual's FB165 example).
  EXPECT_EQ(m.data_job(job(20, 0, 104, 0, 10, 0), plc), ok(70));
  EXPECT_EQ(m.axis(1).attributes() & 0x40, 0);  // MD present
  EXPECT_EQ(m.axis(1).error(), 0);
  // No overwrite: a second BA20 is refused by the handling block (DB exists).
  EXPECT_EQ(m.data_job(job(20, 0, 104, 0, 10, 0), plc), interface_error(IfE::db_exists));
  // BA67 read it back (axis tile) into DB204: the image, MD error byte 0.
  EXPECT_EQ(m.data_job(job(67, 0, 10, 0, 204, 0), plc), ok(70));
  EXPECT_EQ(plc[204], make_ip247_md_db(manual_md()));
  // BA64 MD directory: (KY 0,10; KF 70) for axis 1, zeros for axes 2 and 3; from any tile.
  EXPECT_EQ(m.data_job(job(64, data_tile, 0, 0, 205, 0), plc), ok(6));
  EXPECT_EQ(plc[205], (W{10, 70, 0, 0, 0, 0}));
  // BA68 MD overview: per axis DB no., module no., axis no., length, MD error.
  EXPECT_EQ(m.data_job(job(68, 2, 0, 0, 206, 0), plc), ok(15));
  EXPECT_EQ(plc[206], (W{10, 0, 1, 70, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  // BA21 delete needs the right DB number (13), then the set is gone.
  EXPECT_EQ(m.data_job(job(21, 0, 0, 0, 11, 0), plc), module_error(Ip247Error::db_not_present));
  EXPECT_EQ(m.axis(1).error(), 13);  // latched on the axis tile
  EXPECT_EQ(m.data_job(job(21, 0, 0, 0, 10, 0), plc), ok(0));
  EXPECT_NE(m.axis(1).attributes() & 0x40, 0);
  EXPECT_EQ(m.data_job(job(64, 1, 0, 0, 205, 0), plc), ok(6));
  EXPECT_EQ(plc[205], (W{0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(m.data_job(job(67, 0, 10, 0, 204, 0), plc), module_error(Ip247Error::db_not_present));
}

TEST(Ip247Data, ReferencePointSurvivesDeleteAndWriteOfUnchangedMachineData) {
  Ip247Module m;
  auto changed = manual_md();
  changed.jog1 = 1000;  // not reference-relevant
  auto moved = manual_md();
  moved.reference_coordinate = 1000;  // reference-relevant
  S5Blocks plc{{1, make_ip247_md_db(manual_md())}, {2, make_ip247_md_db(changed)}, {3, make_ip247_md_db(moved)}};
  ASSERT_EQ(m.data_job(job(20, 0, 1, 0, 10, 0), plc), ok(70));
  m.command(1, {.ba = 5, .command = Ip247Command::start, .byte_param = 1});  // set reference point
  ASSERT_TRUE(m.axis(1).referenced());
  ASSERT_EQ(m.data_job(job(21, 0, 0, 0, 10, 0), plc), ok(0));
  EXPECT_TRUE(m.axis(1).referenced());  // delete leaves the bit as it was
  ASSERT_EQ(m.data_job(job(20, 0, 2, 0, 10, 0), plc), ok(70));
  EXPECT_TRUE(m.axis(1).referenced());
  ASSERT_EQ(m.data_job(job(21, 0, 0, 0, 10, 0), plc), ok(0));
  ASSERT_EQ(m.data_job(job(20, 0, 3, 0, 10, 0), plc), ok(70));
  EXPECT_FALSE(m.axis(1).referenced());
}

TEST(Ip247Data, FaultyMachineDataAreKeptWithTheirErrorNumber) {
  Ip247Module m;
  auto md = manual_md(12, 2);
  md.pulses_per_rev = 5;  // MD error 5: pulses/rev not 12..1000
  S5Blocks plc{{50, make_ip247_md_db(md)}, {60, W(15, 0)}, {61, W(70, 0)}};
  EXPECT_EQ(m.data_job(job(20, 1, 50, 0, 12, 0), plc),
            (Ip247DataResult{IfE::module, Ip247Error::faulty_machine_data, 70, 0}));
  EXPECT_EQ(m.axis(2).error(), 15);
  EXPECT_EQ(m.axis(2).attributes() & 0x40, 0);  // "MD missing" clears even for a faulty set
  EXPECT_EQ(m.data_job(job(68, data_tile, 0, 0, 60, 0), plc), ok(15));
  EXPECT_EQ(plc[60], (W{0, 0, 0, 0, 0, 12, 0, 2, 70, 5, 0, 0, 0, 0, 0}));
  EXPECT_EQ(m.data_job(job(67, 1, 12, 0, 61, 0), plc), ok(70));
  EXPECT_EQ(plc[61][4], 0x0105);  // unit mm, MD error 5 in DR 4
  // Motion commands: 14 "no or wrong MD".
  m.command(2, {.ba = 7, .command = Ip247Command::forward, .value = 1000});
  EXPECT_EQ(m.axis(2).error(), 14);
  // The MD of axis 2 sent on the tile of axis 1: 46.
  md.pulses_per_rev = 200;
  plc[51] = make_ip247_md_db(md);
  EXPECT_EQ(m.data_job(job(20, 0, 51, 0, 12, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
}

TEST(Ip247Data, WrongTilesAndInterfaceErrors) {
  Ip247Module m(4);  // tiles 4..7
  S5Blocks plc{{104, make_ip247_md_db(manual_md())}, {5, W(10, 0)}, {6, W(3, 0)}};
  EXPECT_EQ(m.channel(4), 1);
  EXPECT_EQ(m.channel(7), 4);
  EXPECT_EQ(m.channel(3), 0);
  EXPECT_EQ(m.data_job(job(20, 0, 104, 0, 10, 0), plc), interface_error(IfE::htb));  // not our tile
  EXPECT_EQ(m.data_job(job(20, 7, 104, 0, 10, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(22, 4, 5, 0, 9, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(66, 7, 0, 0, 5, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(8, 7, 0, 0, 0, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(71, 4, 0, 0, 0, 0), plc), module_error(Ip247Error::job_not_allowed));
  EXPECT_EQ(m.data_channel_error(), 46);  // the data channel's own error
  EXPECT_EQ(m.data_job(job(20, 4, 99, 0, 10, 0), plc), interface_error(IfE::db_missing));
  // From DW1 the length word reads 0044h = 68: not an MD image.
  EXPECT_EQ(m.data_job(job(20, 4, 104, 1, 10, 0), plc), interface_error(IfE::wrong_identifier));
  EXPECT_EQ(m.data_job(job(20, 4, 104, 0, 11, 0), plc), interface_error(IfE::wrong_identifier));  // 'B',10 != 11
  EXPECT_EQ(m.data_job(job(20, 4, 104, 70, 10, 0), plc), interface_error(IfE::offset_too_large));
  EXPECT_EQ(m.data_job(job(70, 5, 0, 0, 6, 0), plc), interface_error(IfE::target_too_small));  // 9 words into 3
  EXPECT_EQ(m.data_job(job(70, 5, 0, 0, 5, 0), plc), ok(9));
  // BA17 on an axis clears the data channel's error too.
  EXPECT_EQ(m.data_job(job(71, 7, 0, 0, 0, 0), plc), module_error(Ip247Error::job_not_allowed));
  m.command(2, {.ba = 17});
  EXPECT_EQ(m.data_channel_error(), 0);
}

TEST(Ip247Data, ProgramWriteReadDeleteWithTheManualImage) {
  Ip247Module m;
  W bad = vp_image(7, "%7\nN10 X100 F1000\nN20 X200\nN30 M02\n");
  S5Blocks plc{{101, manual_vp}, {107, bad}, {201, W(30, 0xFFFF)}, {202, W(20, 0)}};
  EXPECT_EQ(m.data_job(job(22, data_tile, 101, 0, 1, 0), plc), ok(25));
  ASSERT_NE(m.programs().find(1), nullptr);
  EXPECT_EQ(*m.programs().text(1), "%  1 BEISPIEL\nN1 X100 F1000 M10\nN2 M02\n");
  // BA69 read (any tile) gives the image word for word.
  EXPECT_EQ(m.data_job(job(69, 0, 1, 0, 201, 2), plc), ok(25));
  EXPECT_EQ(W(plc[201].begin() + 2, plc[201].begin() + 27), manual_vp);
  EXPECT_EQ(plc[201][0], 0xFFFF);  // nothing outside the target area
  EXPECT_EQ(plc[201][27], 0xFFFF);
  EXPECT_EQ(m.data_job(job(69, 0, 1, 0, 202, 0), plc), interface_error(IfE::target_too_small));
  // No overwrite (49); a faulty program (X without F in N20: syntax error 6) is refused with 48,
  // its image with the syntax error in DW3 and the block in DW4 is readable, it is not stored.
  EXPECT_EQ(m.data_job(job(22, data_tile, 101, 0, 1, 0), plc), module_error(Ip247Error::program_exists));
  EXPECT_EQ(m.data_job(job(22, data_tile, 107, 0, 7, 0), plc), module_error(Ip247Error::program_faulty));
  EXPECT_EQ(m.data_channel_error(), 48);
  EXPECT_EQ(m.programs().find(7), nullptr);
  EXPECT_EQ(m.data_job(job(69, data_tile, 7, 0, 201, 0), plc), ok(static_cast<int>(bad.size())));
  EXPECT_EQ(plc[201][3], 6);
  EXPECT_EQ(plc[201][4], 20);
  EXPECT_EQ(m.programs().directory().size(), 1U);
  // Start of the refused program: 13 (not present).
  m.command(1, {.ba = 8, .command = Ip247Command::start, .byte_param = 7});
  // BA23 delete: 13 for a program that is not there; on an axis tile 46.
  EXPECT_EQ(m.data_job(job(23, data_tile, 0, 0, 9, 0), plc), module_error(Ip247Error::db_not_present));
  EXPECT_EQ(m.data_job(job(23, 1, 0, 0, 1, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(23, data_tile, 0, 0, 1, 0), plc), ok(0));
  EXPECT_EQ(m.programs().find(1), nullptr);
  EXPECT_EQ(m.programs().used_chars(), 0U);
  // Source DB shorter than the image's length word: B; longer than 512 words: C.
  plc[102] = W(manual_vp.begin(), manual_vp.begin() + 20);
  EXPECT_EQ(m.data_job(job(22, data_tile, 102, 0, 1, 0), plc), interface_error(IfE::source_too_small));
  plc[102][0] = 600;
  EXPECT_EQ(m.data_job(job(22, data_tile, 102, 0, 1, 0), plc), interface_error(IfE::source_too_large));
}

TEST(Ip247Data, ProgramDirectorySplitOverTwoBlocks) {
  // Manual example 2 (§6.3.8.5): 3 programs, ZANF = 253 -> entry 1 in DBx DW253/254 (DW255
  // exists, not written), entries 2 and 3 in DBx+1 DW0..DW3.
  Ip247Module m;
  S5Blocks plc;
  for (int n : {5, 3, 9}) {
    plc[100] = vp_image(n, "%" + std::to_string(n) + "\nN1 X" + std::to_string(n) + " F100\nN2 M02\n");
    ASSERT_EQ(m.data_job(job(22, data_tile, 100, 0, n, 0), plc).module_error, Ip247Error::none);
  }
  plc[40] = W(256, 0xEEEE);
  plc[41] = W(4, 0xEEEE);
  EXPECT_EQ(m.data_job(job(65, 0, 0, 0, 40, 253), plc), ok(6));
  EXPECT_EQ(plc[40][252], 0xEEEE);
  EXPECT_EQ(plc[40][253], 5);   // KY 0,5 (storage order, not sorted)
  EXPECT_EQ(plc[40][254], 16);  // "%5\nN1 X5 F100\nN2 M02\n" = 21 chars -> 5 + 11 words
  EXPECT_EQ(plc[40][255], 0xEEEE);
  EXPECT_EQ(plc[41], (W{3, 16, 9, 16}));
  // Without DBx+1, or DBx not reaching DW255, or DBx+1 too short: the job is refused.
  plc.erase(41);
  EXPECT_EQ(m.data_job(job(65, 0, 0, 0, 40, 253), plc), interface_error(IfE::db_missing));
  plc[41] = W(3, 0);
  EXPECT_EQ(m.data_job(job(65, 0, 0, 0, 40, 253), plc), interface_error(IfE::target_too_small));
  plc[40] = W(255, 0);
  plc[41] = W(4, 0);
  EXPECT_EQ(m.data_job(job(65, 0, 0, 0, 40, 253), plc), interface_error(IfE::target_too_small));
  // Fits into DBx: no DBx+1 needed.
  plc[40] = W(10, 0);
  plc.erase(41);
  EXPECT_EQ(m.data_job(job(65, data_tile, 0, 0, 40, 2), plc), ok(6));
  EXPECT_EQ(plc[40], (W{0, 0, 5, 16, 3, 16, 9, 16, 0, 0}));
}

TEST(Ip247Data, ProgramDirectoryOf255ProgramsFillsTwoBlocks) {
  // Manual example 1: 255 programs, ZANF = 0 -> entries 1..128 in DBx DW0..DW255, 129..255 in
  // DBx+1 DW0..DW253.
  Ip247Module m;
  S5Blocks plc;
  for (int n = 1; n <= 255; ++n) {
    plc[1] = vp_image(n, "%" + std::to_string(n) + "\nN1 M02\n");
    ASSERT_EQ(m.data_job(job(22, data_tile, 1, 0, n, 0), plc).module_error, Ip247Error::none) << n;
  }
  plc[1] = vp_image(0, "%0\nN1 M02\n");
  EXPECT_EQ(m.data_job(job(22, data_tile, 1, 0, 0, 0), plc), module_error(Ip247Error::max_programs));
  plc[20] = W(256, 0);
  plc[21] = W(256, 0xEEEE);
  EXPECT_EQ(m.data_job(job(65, 0, 0, 0, 20, 0), plc), ok(510));
  EXPECT_EQ(plc[20][0], 1);
  EXPECT_EQ(plc[20][1], 10);  // "%1\nN1 M02\n" = 10 chars -> 5 + 5 words
  EXPECT_EQ(plc[20][254], 128);
  EXPECT_EQ(plc[21][0], 129);
  EXPECT_EQ(plc[21][252], 255);
  EXPECT_EQ(plc[21][253], 11);  // "%255\nN1 M02\n" = 12 chars -> 5 + 6 words
  EXPECT_EQ(plc[21][254], 0xEEEE);
}

TEST(Ip247Data, ActualValuesBinaryAndBcd) {
  Ip247Module m;
  S5Blocks plc{{1, make_ip247_md_db(manual_md())}, {30, W(6, 0xFFFF)}};
  ASSERT_EQ(m.data_job(job(20, 0, 1, 0, 10, 0), plc), ok(70));
  // BA12: the actual value becomes 47.287 mm (the manual's BA66 example 0000 B8B7h).
  m.command(1, {.ba = 12, .command = Ip247Command::start, .value = 47'287});
  ASSERT_EQ(m.axis(1).actual(), 47'287);
  EXPECT_EQ(m.data_job(job(66, 0, 0, 0, 30, 0), plc), ok(6));
  EXPECT_EQ(plc[30], (W{0x0000, 0xB8B7, 0, 0, 0, 0}));
  m.command(1, {.ba = 12, .command = Ip247Command::start, .value = -120'000});
  EXPECT_EQ(m.data_job(job(66, 0, 0, 0, 30, 0, true), plc), ok(6));  // KY 255,66
  EXPECT_EQ(plc[30], (W{0xF012, 0x0000, 0, 0, 0, 0}));
  // Not convertible (beyond +-9 999 999): binary, flagged in MB249 bit 0.
  m.command(1, {.ba = 12, .command = Ip247Command::start, .value = 12'345'678});
  EXPECT_EQ(m.data_job(job(66, 0, 0, 0, 30, 0, true), plc), (Ip247DataResult{IfE::none, Ip247Error::none, 6, 1}));
  EXPECT_EQ(plc[30][0], 0x00BC);
  EXPECT_EQ(plc[30][1], 0x614E);
}

TEST(Ip247Data, SysIdWriteAndRead) {
  Ip247Module m;
  S5Blocks plc{{2, W{7, 12, 84}}, {3, W(9, 0)}, {4, make_ip247_md_db(manual_md())}, {5, W{3, 0, 0}}, {6, W{100, 0, 0}}};
  EXPECT_EQ(m.data_job(job(24, 0, 2, 0, 0, 0), plc), module_error(Ip247Error::mode_not_allowed_on_axis));
  EXPECT_EQ(m.data_job(job(24, data_tile, 2, 0, 0, 0), plc), ok(3));
  EXPECT_EQ(m.sysid(), (Ip247SysId{7, 12, 84}));
  EXPECT_EQ(m.data_job(job(70, 1, 0, 0, 3, 0), plc), ok(9));
  EXPECT_EQ(plc[3], (W{0x4950, 0x3234, 0x3720, 0x4130, 0x322E, 0x3120, 7, 12, 84}));  // "IP247 A02.1 "
  // The MD carry module 0: refused with MD error 12 under SYS-ID 7; with SYS-ID 0 accepted, and
  // then the module number cannot change (12).
  EXPECT_EQ(m.data_job(job(20, 0, 4, 0, 10, 0), plc).module_error, Ip247Error::faulty_machine_data);
  EXPECT_EQ(m.md_image(1)->at(4) & 0xFF, 12);
  ASSERT_EQ(m.data_job(job(21, 0, 0, 0, 10, 0), plc), ok(0));
  EXPECT_EQ(m.data_job(job(24, data_tile, 6, 0, 0, 0), plc), module_error(Ip247Error::job_not_allowed));  // 100
  plc[2] = W{0, 0, 0};
  ASSERT_EQ(m.data_job(job(24, data_tile, 2, 0, 0, 0), plc), ok(3));
  ASSERT_EQ(m.data_job(job(20, 0, 4, 0, 10, 0), plc), ok(70));
  EXPECT_EQ(m.data_job(job(24, data_tile, 5, 0, 0, 0), plc), module_error(Ip247Error::module_number_locked));
}

TEST(Ip247Data, DeletingBeforeARunningProgramLeavesAGap) {
  Ip247Module m;
  S5Blocks plc{{1, make_ip247_md_db(manual_md())}};
  ASSERT_EQ(m.data_job(job(20, 0, 1, 0, 10, 0), plc), ok(70));
  const std::string p1 = "%1\nN1 X10 F100\nN2 M02\n";
  const std::string p2 = "%2\nN1 X100 F1000\nN2 M02\n";
  plc[100] = vp_image(1, p1);
  ASSERT_EQ(m.data_job(job(22, data_tile, 100, 0, 1, 0), plc), ok(static_cast<int>(plc[100].size())));
  plc[100] = vp_image(2, p2);
  ASSERT_EQ(m.data_job(job(22, data_tile, 100, 0, 2, 0), plc), ok(static_cast<int>(plc[100].size())));
  m.command(1, {.ba = 5, .command = Ip247Command::start, .byte_param = 1});
  m.command(1, {.ba = 8, .command = Ip247Command::start, .byte_param = 2});
  std::int64_t t = 0;
  m.axis(1).step(t, 1'000'000, {}, nullptr);
  ASSERT_TRUE(m.axis(1).running());
  // Program 2 runs: deleting it is refused (51); deleting program 1 before it leaves a gap (61).
  EXPECT_EQ(m.data_job(job(23, data_tile, 0, 0, 2, 0), plc), module_error(Ip247Error::program_active));
  EXPECT_EQ(m.data_job(job(23, data_tile, 0, 0, 1, 0), plc), module_error(Ip247Error::deleted_from_directory_only));
  EXPECT_EQ(m.programs().find(1), nullptr);
  EXPECT_EQ(m.programs().gap_chars(), p1.size());
  EXPECT_EQ(m.programs().used_chars(), p1.size() + p2.size());
  while (m.axis(1).running() && t < 60'000'000'000) m.axis(1).step(t += 1'000'000, 1'000'000, {}, nullptr);
  ASSERT_FALSE(m.axis(1).running());
  // Program 2 ended: deleting it compacts the memory.
  EXPECT_EQ(m.data_job(job(23, data_tile, 0, 0, 2, 0), plc), ok(0));
  EXPECT_EQ(m.programs().used_chars(), 0U);
  EXPECT_EQ(m.programs().gap_chars(), 0U);
}

TEST(Ip247Data, NoProgramChangeDuringTeachIn) {
  Ip247Module m;
  S5Blocks plc{{1, make_ip247_md_db(manual_md())}, {100, vp_image(3, "%3\nN1 M02\n")}};
  ASSERT_EQ(m.data_job(job(20, 0, 1, 0, 10, 0), plc), ok(70));
  m.command(1, {.ba = 5, .command = Ip247Command::start, .byte_param = 1});
  m.command(1, {.ba = 10, .command = Ip247Command::start, .byte_param = 7});
  ASSERT_TRUE(m.axis(1).teach_in());
  EXPECT_EQ(m.data_job(job(22, data_tile, 100, 0, 3, 0), plc), module_error(Ip247Error::teach_in_exclusive));
  m.command(1, {.ba = 11, .command = Ip247Command::start});
  EXPECT_EQ(m.data_job(job(22, data_tile, 100, 0, 3, 0), plc), ok(static_cast<int>(plc[100].size())));
}

TEST(Ip247Data, JobBlockCodec) {
  W block{0xFF42, 101, 2, 7, 3, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const auto j = take_ip247_data_job(block);
  ASSERT_TRUE(j);
  EXPECT_EQ(j->ba, 0x42);
  EXPECT_TRUE(j->bcd);
  EXPECT_EQ(j->q_db, 101);
  EXPECT_EQ(j->q_start, 2);
  EXPECT_EQ(j->z_db, 7);
  EXPECT_EQ(j->z_start, 3);
  EXPECT_EQ(j->tile, 4);
  write_ip247_data_result(block, {IfE::module, Ip247Error::program_faulty, 0, 0});
  EXPECT_EQ(block, (W{0, 101, 2, 7, 3, 4, 1 | 2, 0x0230, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_FALSE(take_ip247_data_job(block));
  write_ip247_data_result(block, {IfE::none, Ip247Error::none, 25, 2});
  EXPECT_EQ(block, (W{0, 101, 2, 7, 3, 4, 0, 0, 2, 25, 0, 0, 0, 0, 0}));
}
