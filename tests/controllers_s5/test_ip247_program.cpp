// SPDX-License-Identifier: MIT
// IP247 traversing-program syntax check (digest ip247.md §3.2-3.11, §6.3) and the VP DB image
// (§5.5 b): the manual's programs parse; each rule violation gives the module's number and block.
#include <gtest/gtest.h>

#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

using namespace hil::controllers::s5;
using E = Ip247SyntaxError;

TEST(Ip247Program, ManualProgramsParse) {
  const char* programs[] = {
      "%  1 BEISPIEL\nN1 X100 F1000 M10\nN2 M02\n",
      "%9              Programmbeispiel\nN10 G74 M10\nN20 G24 F5\nN30 L36\nN40 X50 F2000\nN50 G20\nN60 M02\n",
      "%155 BEISPIEL EINES VERFAHRPROGRAMMS\nN10 G74 M10\nN11 G04 F50 M11\nN20 G00 X110.500 M20\nN25 G24 F7\n"
      "N30 X-200.000 F4500 M30\nN35 G10 X-50.000 F400 M35\nN40 X150.000 F2000 M40\nN45 G20\nN99 M02\n",
      "L12         das ist ein Unterprogramm im DB12\nN1 X0 F100 M10\nN2 G04 F50\nN7 M02\n",
      "% 5\nN05 G91\nN10 G74\nN15 G24 F3\nN20 X1000 F2000 M10\nN30 G57\nN35 X-500 F2000\nN45 G20\nN50 G74 M20\n"
      "N60 X500 F100 M30\nN65 G26\nN70 X1000 F2000 M60\nN75 M02\n",
      "%1\nN10 X50 F1000\nN20 X50. F1000\nN30 X-5 F1000\nN40 X+12345.678 F1000\n/N50 X1 F1\n:N60 X2 F2\n  N70 M02  \n",
      "%4\nN10 X100 F1000 M00\nN15 M00\nN20 G56 M00\nN25 G43 X200 F100 M02\n",
  };
  for (const char* text : programs) {
    auto p = parse_ip247_program(text);
    ASSERT_TRUE(p) << text << "\n-> " << p.error().message;
    EXPECT_TRUE(p->blocks.back().is_final());
  }
  auto p = parse_ip247_program(programs[2]);
  EXPECT_EQ(p->number, 155);
  EXPECT_EQ(p->title, "BEISPIEL EINES VERFAHRPROGRAMMS");
  EXPECT_EQ(p->blocks[2].g, 0);
  EXPECT_EQ(p->blocks[2].x_milli, 110'500);
  EXPECT_EQ(p->blocks[3].partner, 7);
  EXPECT_EQ(p->blocks[7].partner, 3);
  auto q = parse_ip247_program(programs[5]);
  EXPECT_EQ(q->blocks[1].x_milli, 50'000);
  EXPECT_EQ(q->blocks[2].x_milli, -5'000);
  EXPECT_EQ(q->blocks[3].x_milli, 12'345'678);
  EXPECT_EQ(q->blocks[4].kind, '/');
  auto sub = parse_ip247_program(programs[3]);
  EXPECT_TRUE(sub->subprogram);
  EXPECT_EQ(sub->number, 12);
}

struct BadCase {
  const char* text;
  E code;
  int block;
};

TEST(Ip247Program, SyntaxErrorsCarryTheModuleNumberAndBlock) {
  const BadCase cases[] = {
      {"%1 no line feed", E::text_too_long, 0},
      {"#1\nN1 M02\n", E::block_type, 0},
      {"%1\nX100 F10\nN2 M02\n", E::block_type, 0},
      {"%1\nN1000 M02\n", E::block_number_too_large, 0},
      {"%1\nN10 L256\nN20 M02\n", E::subprogram_number, 10},
      {"%300\nN10 M02\n", E::subprogram_number, 0},
      {"%1\nN10 G00 F100\nN20 M02\n", E::function_after_g, 10},
      {"%1\nN10 G04 X10 F10\nN20 M02\n", E::function_after_g, 10},
      {"%1\nN10 G20 M10\nN20 M02\n", E::function_after_g, 10},
      {"%1\nN10 G24 F3 M10\nN15 G20\nN20 M02\n", E::function_after_g, 10},
      {"%1\nN10 G74 X100\nN20 M02\n", E::function_after_g, 10},
      {"%1\nN10 X100 M10\nN20 M02\n", E::function_after_x, 10},
      {"%1\nN10 X100 G90 F10\nN20 M02\n", E::function_after_x, 10},
      {"%1\nN10 G00 X100 F10\nN20 M02\n", E::function_after_x, 10},
      {"%1\nN10 X100 F10\nN20 M02", E::final_block_lf, 20},
      {"%1\nN10 L5 M10\nN20 M02\n", E::block_end, 10},
      {"%1\nN10 F100\nN20 M02\n", E::block_end, 10},
      {"%1\nN10 M10 X5\nN20 M02\n", E::block_end, 10},
      {"%1\nN10G90\nN20 M02\n", E::block_end, 10},
      {"%1\nN10 X123456 F10\nN20 M02\n", E::path_too_large, 10},
      {"%1\nN10 X1 F65001\nN20 M02\n", E::f_too_large, 10},
      {"%1\nN10 X1 F0\nN20 M02\n", E::f_too_large, 10},
      {"%1\nN10 X1.2345 F10\nN20 M02\n", E::too_many_decimals, 10},
      {"%1\nN10 G24 F2\nN20 X1 F10\nN30 M02\n", E::loop_end_missing, 30},
      {"%1\nN10 X1 F10\nN20 G20\nN30 M02\n", E::loop_start_missing, 20},
      {"%1\nN10 X1 F10\n", E::program_end_missing, 10},
      {"%1\nN10 X1 F10 Q5\nN20 M02\n", E::unknown_function, 10},
      {"%1\nN10 X1 F10 M100\nN20 M02\n", E::m_too_large, 10},
      {"%1\nN10 M02\nN20 X1 F10\n", E::block_after_final, 10},
      {"%1\nN10 X1 F10 M10                                        \nN20 M02\n", E::block_too_long, 10},
      {"%1\nN10 G05 X1 F10\nN20 M02\n", E::g_not_implemented, 10},
      {"%1\nN10 G100 X1 F10\nN20 M02\n", E::g_not_implemented, 10},
  };
  for (const auto& c : cases) {
    auto p = parse_ip247_program(c.text);
    ASSERT_FALSE(p) << c.text;
    EXPECT_EQ(p.error().code, c.code) << c.text << " -> " << p.error().message;
    EXPECT_EQ(p.error().block_number, c.block) << c.text;
    EXPECT_FALSE(p.error().message.empty());
  }
  std::string big = "%1\n";
  while (big.size() < 1030) big += "N1 X1 F1\n";
  big += "N2 M02\n";
  auto p = parse_ip247_program(big);
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().code, E::text_too_long);
  EXPECT_EQ(make_error_code(E::block_too_long).category().name(), std::string("ip247-syntax"));
}

TEST(Ip247Program, CanonicalTextRoundTrips) {
  auto p = parse_ip247_program("% 7\nN1 X1258.25 F2500\nN2 G91 X-3 F10 M00\n/N3 L9\nN4 G04 F5 M11\nN5 M02\n");
  ASSERT_TRUE(p);
  const std::string text = make_ip247_program_text(*p);
  EXPECT_EQ(text, "%  7\nN1 X1258.250 F2500\nN2 G91 X-3.000 F10 M00\n/N3 L9\nN4 G04 F5 M11\nN5 M02\n");
  auto q = parse_ip247_program(text);
  ASSERT_TRUE(q);
  for (auto& b : q->blocks) b.line = 0;
  for (auto& b : p->blocks) b.line = 0;
  EXPECT_EQ(*p, *q);
}

TEST(Ip247ProgramDb, ManualImageWordForWord) {
  // §6.3.8.2 / digest §5.5 b: "%  1 BEISPIEL / N1 X100 F1000 M10 / N2 M02", 25 words.
  const std::vector<std::uint16_t> expect{25,     0x0044, 0x4201, 0,      0,      0x2520, 0x2031, 0x2042, 0x4549,
                                          0x5350, 0x4945, 0x4C0A, 0x4E31, 0x2058, 0x3130, 0x3020, 0x4631, 0x3030,
                                          0x3020, 0x4D31, 0x300A, 0x4E32, 0x204D, 0x3032, 0x0A00};
  const std::string text = "%  1 BEISPIEL\nN1 X100 F1000 M10\nN2 M02\n";
  auto w = make_ip247_vp_db({.db = 1, .text = text});
  ASSERT_TRUE(w);
  EXPECT_EQ(*w, expect);
  auto back = parse_ip247_vp_db(expect);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->text, text);
  EXPECT_EQ(back->db, 1);
  auto p = parse_ip247_program(back->text);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->number, 1);
  EXPECT_EQ(p->title, "BEISPIEL");
}

TEST(Ip247ProgramDb, RejectedImagesAndErrorWords) {
  EXPECT_FALSE(parse_ip247_vp_db({3, 0x44, 0x4201}));
  EXPECT_FALSE(parse_ip247_vp_db({30, 0x44, 0x4201, 0, 0, 0x2520}));  // length beyond the image
  EXPECT_FALSE(parse_ip247_vp_db({6, 0x45, 0x4201, 0, 0, 0x2520}));   // not 'D'
  EXPECT_FALSE(make_ip247_vp_db({.db = 1, .text = std::string(1100, 'N')}));
  auto w = make_ip247_vp_db({.db = 3, .text = "%3\nN10 X1 F10 M100\nN20 M02\n"});
  ASSERT_TRUE(w);
  auto back = parse_ip247_vp_db(*w);
  auto p = parse_ip247_program(back->text);
  ASSERT_FALSE(p);
  set_ip247_vp_error(*w, p.error());
  EXPECT_EQ((*w)[3], 17);
  EXPECT_EQ((*w)[4], 10);
}
