// SPDX-License-Identifier: MIT
// WF 725/726 program input/output by data codes 44/45 through user data blocks (401/402, 201,
// syntax errors of the memory administration, nothing half-stored), and the RK512 data-block
// policy of `hilbridge emulate wf725` (DB axis, MD image DB 1, user DBs) on virtual time.
#include "hil/controllers/s5/wf725_module_endpoint.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "wf725_fixture.hpp"

namespace hil::controllers::s5::test {
namespace {

using W = Wf725Fixture;
using serial::s5::Rk512Error;

std::vector<std::uint16_t> text_words(const std::string& text) {
  std::vector<std::uint16_t> w{static_cast<std::uint16_t>(text.size())};
  for (std::size_t i = 0; i < text.size(); i += 2) {
    const auto hi = static_cast<std::uint8_t>(text[i]);
    const auto lo = i + 1 < text.size() ? static_cast<std::uint8_t>(text[i + 1]) : 0;
    w.push_back(static_cast<std::uint16_t>(hi << 8 | lo));
  }
  return w;
}

void put_db(Wf725Controller& c, int db, const std::vector<std::uint16_t>& w) {
  for (std::size_t i = 0; i < w.size(); ++i) ASSERT_TRUE(c.write_data_word(db, static_cast<int>(i), w[i]));
}

TEST_F(W, ProgramInputAndOutputByDataCodes) {
  start(base_md());
  put_db(*ctl, 20, text_words("%7 A\nN1 G90 X 20 000 F 300 000\nN2 G91 X -5000 F 100 000 M21\n"));
  data_code(db::code::program_in, 20);
  EXPECT_EQ(io_error(), 0x0201) << "outside mode program input/output";
  EXPECT_EQ(ctl->programs().find(7), nullptr);
  select(db::bit_mode_program_io, db::Submode::none);
  data_code(db::code::program_in, 20);
  EXPECT_EQ(io_error(), 0);
  ASSERT_NE(ctl->programs().find(7), nullptr);
  EXPECT_EQ(ctl->programs().find(7)->blocks.size(), 2U);
  // A faulty text: the memory administration's number, nothing of it stored.
  put_db(*ctl, 21, text_words("%8\nN1 G90 X 10 F 100\n%9\nN1 G04\n"));
  data_code(db::code::program_in, 21);
  EXPECT_EQ(io_error(), 0x0236);  // G04 without time value
  EXPECT_EQ(ctl->programs().find(8), nullptr);
  // Interpolation pairs are checked on input too: 174 / 181 (program I/O) in DW 40, nothing stored.
  put_db(*ctl, 25, text_words("%10\nN1 X 1 F 100\n%11\nN1 A G18 X 1 F 100\nN2 B X 2\n"));
  data_code(db::code::program_in, 25);
  EXPECT_EQ(io_error(), 0x0174);
  EXPECT_EQ(ctl->programs().find(10), nullptr);
  put_db(*ctl, 25, text_words("%10\nN1 X 1 F 100\n%11\nN4 A G17 X 1 F 100\nN2 B X 2\n"));
  data_code(db::code::program_in, 25);
  EXPECT_EQ(io_error(), 0x0181);
  EXPECT_EQ(ctl->programs().find(10), nullptr);
  data_code(db::code::program_in, 33);
  EXPECT_EQ(io_error(), 0x0401);  // no such user DB
  // Output into DB 22 reads back as the same program.
  data_code(db::code::program_out, 7, 22);
  EXPECT_EQ(io_error(), 0);
  const auto& out = ctl->user_blocks().at(22);
  std::string text;
  for (std::size_t i = 0; i < out[0]; ++i)
    text.push_back(static_cast<char>(i % 2 ? out[1 + i / 2] & 0xFF : out[1 + i / 2] >> 8));
  auto back = parse_wf725_programs(text);
  ASSERT_TRUE(back) << text;
  EXPECT_EQ(back->front(), *ctl->programs().find(7));
  data_code(db::code::program_out, 5, 22);
  EXPECT_EQ(io_error(), 0x0127);
  data_code(db::code::program_out, 0, 22);
  EXPECT_EQ(io_error(), 0x0125);
  // A program longer than a user DB holds (255 words = 510 characters): 402.
  std::string big = "%9\n";
  for (int n = 1; n <= 40; ++n) big += "N" + std::to_string(n) + " G90 X " + std::to_string(n * 1000) + " F 100000\n";
  ASSERT_EQ(ctl->store_program(parse_wf725_programs(big)->front()), 0);
  data_code(db::code::program_out, 9, 23);
  EXPECT_EQ(io_error(), 0x0402);
  EXPECT_FALSE(ctl->user_blocks().contains(23));
  // All or nothing: RAM holds 50 blocks; with 45 used, a text of two 3-block RAM programs is
  // refused (123) and neither of them is stored.
  std::string ram = "%30 RAM\n";
  for (int n = 1; n <= 45; ++n) ram += "N" + std::to_string(n) + " G90 X 1 F 100\n";
  ASSERT_EQ(ctl->store_program(parse_wf725_programs(ram)->front()), 0);
  put_db(*ctl, 24, text_words("%31 RAM\nN1 X1 F1\nN2 X2 F1\nN3 X3 F1\n%32 RAM\nN1 X1 F1\nN2 X2 F1\nN3 X3 F1\n"));
  data_code(db::code::program_in, 24);
  EXPECT_EQ(io_error(), 0x0123);
  EXPECT_EQ(ctl->programs().find(31), nullptr);
  EXPECT_EQ(ctl->programs().find(32), nullptr);
}

TEST_F(W, AutomaticBufferRunsReloadsAndChangesWithM12) {
  auto md = base_md();
  md[8] = "10";  // timed M output: M11/M12 need no handshake
  start(md);
  synchronize();
  traverse(db::Submode::automatic_buffer);
  // Setting the length: buffer 0 155, another axis' buffer 151, more than 50 blocks 152.
  data_code(db::code::buffer_length, 0, 2);
  EXPECT_EQ(io_error(), 0x0155);
  data_code(db::code::buffer_length, 3, 2);
  EXPECT_EQ(io_error(), 0x0151);
  data_code(db::code::buffer_length, 1, 51);
  EXPECT_EQ(io_error(), 0x0152);
  // Reloading: no length yet 143; not from N1 144; N 51 147; a block of a number only 146; more
  // blocks than the length 143; nothing of a refused reload is taken.
  put_db(*ctl, 20, text_words("N1 G90 X 10 000 F 300 000\nN2 G90 X 20 000 F 300 000 M12\n"));
  data_code(db::code::buffer_reload, 1, 20);
  EXPECT_EQ(io_error(), 0x0143);
  data_code(db::code::buffer_length, 1, 2);
  EXPECT_EQ(io_error(), 0);
  put_db(*ctl, 21, text_words("N2 G90 X 1 F 100\n"));
  data_code(db::code::buffer_reload, 1, 21);
  EXPECT_EQ(io_error(), 0x0144);
  put_db(*ctl, 22, text_words("N51 G90 X 1 F 100\n"));
  data_code(db::code::buffer_reload, 1, 22);
  EXPECT_EQ(io_error(), 0x0147);
  put_db(*ctl, 23, text_words("N1\n"));
  data_code(db::code::buffer_reload, 1, 23);
  EXPECT_EQ(io_error(), 0x0146);
  put_db(*ctl, 24, text_words("N1 G90 X 1 F 100\nN2 G90 X 2 F 100\nN3 G90 X 3 F 100\n"));
  data_code(db::code::buffer_reload, 1, 24);
  EXPECT_EQ(io_error(), 0x0143);
  EXPECT_TRUE(ctl->buffer(1).program.blocks.empty());
  data_code(db::code::buffer_reload, 1, 20);
  EXPECT_EQ(io_error(), 0);
  EXPECT_TRUE(ctl->buffer(1).complete());
  // Starting: another axis' buffer B0, an incomplete buffer B1.
  ctl->write_db_word(db::dw_program, 3);
  start_pulse();
  EXPECT_EQ(error(), 0xB0);
  ctl->write_db_word(db::dw_program, 2);
  start_pulse();
  EXPECT_EQ(error(), 0xB1);
  // Buffer 2: one block, loaded in two reloads of part of it is not possible (length 1).
  data_code(db::code::buffer_length, 2, 1);
  put_db(*ctl, 25, text_words("N1 G90 X 5 000 F 300 000\n"));
  data_code(db::code::buffer_reload, 2, 25);
  EXPECT_EQ(io_error(), 0);
  // Run buffer 1: N1, N2 with M12 -> buffer 2 -> end at 5 mm. Reloading the running buffer: 203.
  ctl->write_db_word(db::dw_program, 1);
  start_pulse();
  EXPECT_EQ(error(), 0);
  data_code(db::code::buffer_reload, 1, 20);
  EXPECT_EQ(io_error(), 0x0203);
  ASSERT_TRUE(run_until([&] { return !bit(db::dw_flags, 1) && bit(db::dw_status, db::bit_peh); }));
  run(milliseconds(300));  // settles inside the PEH window
  EXPECT_EQ(actual(), 5000);
  EXPECT_EQ(error(), 0);
  EXPECT_EQ(ctl->m_history(), (std::vector<int>{12}));
  // Both buffers ran and are consumed: a new start needs a reload (B1).
  EXPECT_FALSE(ctl->buffer(1).complete());
  EXPECT_FALSE(ctl->buffer(2).complete());
  start_pulse();
  EXPECT_EQ(error(), 0xB1);
  // M11 in an odd buffer: B2 at the start.
  data_code(db::code::buffer_length, 1, 1);
  put_db(*ctl, 26, text_words("N1 G91 X 100 F 100 000 M11\n"));
  data_code(db::code::buffer_reload, 1, 26);
  ctl->write_db_word(db::dw_program, 1);
  start_pulse();
  EXPECT_EQ(error(), 0xB2);
  // M12 in an even buffer: B3.
  data_code(db::code::buffer_length, 2, 1);
  put_db(*ctl, 27, text_words("N1 G91 X 100 F 100 000 M12\n"));
  data_code(db::code::buffer_reload, 2, 27);
  ctl->write_db_word(db::dw_program, 2);
  start_pulse();
  EXPECT_EQ(error(), 0xB3);
}

TEST_F(W, ModulePolicyServesTheDbAxisMdImageAndUserBlocks) {
  start(base_md());
  Wf725ModulePolicy policy({ctl.get()}, std::chrono::milliseconds(1),
                           [this](const CycleTime&) { run(milliseconds(1)); });
  mocks::legacy::DbStore store;
  policy.share_store(store);
  std::vector<std::uint16_t> out;
  // The DB axis: traversing + set actual value, drive enable, start -> SYN.
  EXPECT_EQ(policy.on_write(store, 10, 0, {0x0103, 0x0000, 0x0001}), Rk512Error::ok);
  policy.on_time(now);
  policy.on_time(now + milliseconds(50));
  EXPECT_EQ(policy.on_write(store, 10, 1, {0x0001}), Rk512Error::ok);
  policy.on_time(now + milliseconds(20));
  ASSERT_EQ(policy.on_read(store, 10, 3, 1, out), Rk512Error::ok);
  EXPECT_TRUE(out[0] & (1U << db::bit_syn)) << out[0];
  EXPECT_EQ(policy.on_read(store, 10, 40, 10, out), Rk512Error::target_too_small);
  // MD image: MD 13 = 96 417 (words 24/25), written only in mode MD I/O.
  ASSERT_EQ(policy.on_read(store, 1, 24, 2, out), Rk512Error::ok);
  EXPECT_EQ((out[0] << 16) | out[1], 96'417);
  EXPECT_EQ(policy.on_write(store, 1, 24, {0x0001, 0x0000}), Rk512Error::processing_not_possible);
  EXPECT_EQ(policy.on_write(store, 10, 0, {0x0400}), Rk512Error::ok);
  policy.on_time(now + milliseconds(20));
  EXPECT_TRUE(ctl->machine_data_mode());
  EXPECT_EQ(policy.on_write(store, 1, 24, {0x0001, 0x0000}), Rk512Error::ok);
  EXPECT_EQ(ctl->machine_data().integer(13), 65'536);
  EXPECT_EQ(policy.on_write(store, 1, 99, {0x0001}), Rk512Error::wrong_identifier);
  EXPECT_EQ(policy.on_write(store, 1, 98, {0, 0, 0, 0}), Rk512Error::target_too_small);  // MD 51
  // User data blocks live in the endpoint's store; data code 44 reads them.
  EXPECT_EQ(policy.on_read(store, 20, 0, 1, out), Rk512Error::db_missing);
  EXPECT_EQ(policy.on_write(store, 20, 0, text_words("%3\nN1 G90 X 5 F 100\n")), Rk512Error::ok);
  EXPECT_TRUE(store.contains(20));
  EXPECT_EQ(policy.on_write(store, 20, 250, std::vector<std::uint16_t>(10, 0)), Rk512Error::target_too_small);
  EXPECT_EQ(policy.on_write(store, 10, 0, {0x0200}), Rk512Error::ok);
  policy.on_time(now + milliseconds(20));
  data_code(db::code::program_in, 20);
  EXPECT_EQ(io_error(), 0);
  EXPECT_NE(ctl->programs().find(3), nullptr);
}

TEST(Wf725ProgramStore, ARunningProgramIsNeverChangedAndStoredProgramsNeverMove) {
  Wf725ProgramStore store;
  auto progs = parse_wf725_programs("%5\nN1 G90 X 100 F 1000\n%6\nN1 G90 X 200 F 1000\n");
  ASSERT_TRUE(progs);
  ASSERT_EQ(store.store((*progs)[0]), 0);
  const Wf725Program* five = store.find(5);
  int running = 5;
  const int id = store.add_user([&](int n) { return n == running; });
  const auto rev = store.revision();
  EXPECT_EQ(store.store((*progs)[0]), 105);  // replace
  EXPECT_EQ(store.remove(5), 105);
  Wf725Block b;
  b.g[0] = 90;
  b.x = 5;
  b.f = 100;
  EXPECT_EQ(store.teach(5, 2, b, false), 105);
  EXPECT_EQ(store.remove_block(5, 1), 105);  // data code 46 through another axis
  EXPECT_EQ(store.revision(), rev);          // refused: nothing changed
  ASSERT_EQ(five->blocks.size(), 1u);
  // Other programs may change while 5 runs; 5 stays where it is.
  for (int n = 10; n < 60; ++n) {
    Wf725Program p = (*progs)[1];
    p.number = n;
    ASSERT_EQ(store.store(std::move(p)), 0) << n;
  }
  EXPECT_EQ(store.teach(6, 3, b, true), 0);
  EXPECT_EQ(store.remove(10), 0);
  const auto before_block = store.revision();
  EXPECT_EQ(store.remove_block(6, 3), 0);
  EXPECT_GT(store.revision(), before_block);  // a deleted block is a change the state file saves
  EXPECT_EQ(store.find(5), five);
  EXPECT_GT(store.revision(), rev);
  running = 0;
  EXPECT_EQ(store.remove(5), 0);
  store.remove_user(id);
  EXPECT_FALSE(store.in_use(6));
}

TEST_F(W, ModulePolicyKeepsTheProgramMemoryInTheStateFile) {
  start(base_md(), "%2\nN1 G90 X 1000 F 10 000\n");
  auto owned = std::make_unique<Wf725ModulePolicy>(std::vector<Wf725Controller*>{ctl.get()}, milliseconds(1),
                                                   [this](const CycleTime&) { run(milliseconds(1)); });
  auto& policy = *owned;
  mocks::legacy::S5BlockEndpoint ep(std::move(owned));
  policy.share_store(ep.store());
  EXPECT_FALSE(ep.take_dirty());  // the programs of the start are not a change
  put_db(*ctl, 20, text_words("%3 A RAM\nN1 G90 X 5 000 F 100 000\nN2 G04 F 200\n"));
  ep.take_dirty();  // the user DB write itself
  select(db::bit_mode_program_io, db::Submode::none);
  data_code(db::code::program_in, 20);
  ASSERT_EQ(io_error(), 0);
  EXPECT_TRUE(ep.take_dirty());  // stored by the data code at the module's cycle: save
  EXPECT_FALSE(ep.take_dirty());
  const std::string saved = ep.save_state();
  EXPECT_NE(saved.find("\"module\""), std::string::npos) << saved;
  EXPECT_NE(saved.find("%3 A RAM"), std::string::npos) << saved;
  // Program 3 deleted, program 2 changed; the state file brings 3 back, the start's 2 wins.
  data_code(db::code::delete_program, 3);
  ASSERT_EQ(io_error(), 0);
  ASSERT_EQ(ctl->programs().find(3), nullptr);
  auto two = parse_wf725_programs("%2\nN1 G90 X 7777 F 10 000\n");
  ASSERT_EQ(ctl->store_program(two->front()), 0);
  ASSERT_TRUE(ep.load_state(saved)) << saved;
  ASSERT_NE(ctl->programs().find(3), nullptr);
  EXPECT_TRUE(ctl->programs().find(3)->ram);
  EXPECT_EQ(ctl->programs().find(3)->blocks.size(), 2U);
  EXPECT_EQ(*ctl->programs().find(2)->blocks[0].x, 7777);
  EXPECT_FALSE(ep.take_dirty());  // loading is not a change to save
  // A saved memory that does not parse is an error naming the line; nothing of it stored.
  const auto bad = ep.load_state(R"({"device":"wf725","dbs":{},"module":"%9\nN1 G90 G91 X 1 F 1\n"})");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().find("line 2"), std::string::npos) << bad.error();
  EXPECT_EQ(ctl->programs().find(9), nullptr);
}

TEST_F(W, ModulePolicyServesSeveralAxesWithOneProgramMemory) {
  start(base_md(), "%7\nN1 G90 X 30 000 F 60 000\n");
  // Axis B of the same module: its own MD list (MD 13 = 50 mm), DB axis 11, no programs of its own.
  auto md_b = base_md();
  md_b[13] = "50000";
  std::string text;
  for (const auto& [n, v] : md_b) text += "MD " + std::to_string(n) + " = " + v + "\n";
  ControllerSpec spec_b = spec;
  spec_b.parameters = write("md-b.txt", text);
  spec_b.programs.clear();
  spec_b.options["axis"] = "B";
  spec_b.options["db"] = "11";
  ControllerRegistry reg;
  register_wf725(reg);
  auto created = reg.create(spec_b);
  ASSERT_TRUE(created) << created.error().describe();
  std::unique_ptr<Wf725Controller> b(static_cast<Wf725Controller*>(created->release()));
  mocks::SimDriveConfig d;
  d.name = "sim:B";
  d.plant.kv_per_s = 200.0;
  d.plant.velocity_lag_s = 0.0;
  d.plant.velocity_feedforward = 1.0;
  motion::Axis axis_b(b->axis_specs()[0].config, std::make_unique<mocks::SimDrive>(d));
  motion::Axis* pb = &axis_b;
  ASSERT_TRUE(b->bind_axes(std::span<motion::Axis* const>(&pb, 1)));
  Wf725ModulePolicy policy({ctl.get(), b.get()}, milliseconds(1), [&](const CycleTime& c) {
    axis->update(c);
    axis_b.update(c);
    if (++tick % every == 0) {
      ctl->step(CycleTime{c.now, ctl->cycle_period()});
      b->step(CycleTime{c.now, b->cycle_period()});
    }
  });
  mocks::legacy::DbStore store;
  policy.share_store(store);
  const auto go = [&](int ms) {
    now += milliseconds(ms);
    policy.on_time(now);
  };
  policy.on_time(now);
  std::vector<std::uint16_t> out;
  const auto word = [&](std::uint8_t db, std::uint8_t dw) {
    EXPECT_EQ(policy.on_read(store, db, dw, 1, out), Rk512Error::ok);
    return out.empty() ? std::uint16_t{0xFFFF} : out[0];
  };
  const auto data_code_b = [&](std::uint16_t code, std::uint16_t p1) {
    EXPECT_EQ(policy.on_write(store, 11, db::dw_data_code, {code}), Rk512Error::ok);
    EXPECT_EQ(policy.on_write(store, 11, db::dd_data_param1, {0, p1}), Rk512Error::ok);
    EXPECT_EQ(policy.on_write(store, 11, db::dw_data_execute, {1}), Rk512Error::ok);
    go(12);
    const auto io = word(11, db::dw_io_error);
    EXPECT_EQ(policy.on_write(store, 11, db::dw_data_execute, {0}), Rk512Error::ok);
    go(12);
    return io;
  };
  // One memory: B sees A's program; the MD images are per axis (DX 1, DX 2), DX 3 does not exist.
  ASSERT_NE(b->programs().find(7), nullptr);
  EXPECT_EQ(b->program_store(), ctl->program_store());
  ASSERT_EQ(policy.on_read_dx(store, 1, 24, 2, out), Rk512Error::ok);
  EXPECT_EQ((out[0] << 16) | out[1], 96'417);
  ASSERT_EQ(policy.on_read_dx(store, 2, 24, 2, out), Rk512Error::ok);
  EXPECT_EQ((out[0] << 16) | out[1], 50'000);
  EXPECT_EQ(policy.on_read_dx(store, 3, 0, 2, out), Rk512Error::db_missing);
  EXPECT_EQ(policy.on_write_dx(store, 2, 24, {0, 1}), Rk512Error::processing_not_possible);  // not in MD I/O
  EXPECT_NE(policy.last_rejection().find("DB11"), std::string::npos) << policy.last_rejection();
  // A runs program 7 (30 mm at 600 mm/min: 3 s).
  EXPECT_EQ(policy.on_write(store, 10, 0, {0x0103, 0x0000, 0x0001}), Rk512Error::ok);
  go(50);
  EXPECT_EQ(policy.on_write(store, 10, 1, {0x0001}), Rk512Error::ok);
  go(20);
  EXPECT_EQ(policy.on_write(store, 10, 1, {0x0000}), Rk512Error::ok);
  EXPECT_EQ(policy.on_write(store, 10, 0, {0x0106}), Rk512Error::ok);
  EXPECT_EQ(policy.on_write(store, 10, db::dw_program, {7}), Rk512Error::ok);
  go(20);
  EXPECT_EQ(policy.on_write(store, 10, 1, {0x0001}), Rk512Error::ok);
  go(200);
  EXPECT_EQ(policy.on_write(store, 10, 1, {0x0000}), Rk512Error::ok);
  ASSERT_TRUE(word(10, db::dw_flags) & 2) << "program 7 runs on A";
  // Through B, in program I/O: deleting or reading in program 7 while A runs it is refused (105).
  EXPECT_EQ(policy.on_write(store, 11, 0, {0x0200}), Rk512Error::ok);
  go(20);
  EXPECT_EQ(data_code_b(db::code::delete_program, 7), 0x0105);
  ASSERT_EQ(policy.on_write(store, 20, 0, text_words("%7\nN1 G90 X 1 000 F 60 000\n")), Rk512Error::ok);
  EXPECT_EQ(data_code_b(db::code::program_in, 20), 0x0105);
  ASSERT_NE(ctl->programs().find(7), nullptr);
  EXPECT_EQ(*ctl->programs().find(7)->blocks[0].x, 30'000);
  // Another program may come in meanwhile; A runs on undisturbed to 30 mm.
  ASSERT_EQ(policy.on_write(store, 21, 0, text_words("%8 B\nN1 G91 X 1 000 F 60 000\n")), Rk512Error::ok);
  EXPECT_EQ(data_code_b(db::code::program_in, 21), 0);
  ASSERT_NE(ctl->programs().find(8), nullptr);
  for (int i = 0; i < 400 && (word(10, db::dw_flags) & 2) != 0; ++i) go(10);
  EXPECT_EQ(static_cast<std::int32_t>((word(10, db::dd_actual) << 16) | word(10, db::dd_actual + 1)), 30'000);
  EXPECT_EQ(word(10, db::dw_error) & 0xFF, 0);
  EXPECT_EQ(data_code_b(db::code::delete_program, 7), 0);
  EXPECT_EQ(ctl->programs().find(7), nullptr);
}

}  // namespace
}  // namespace hil::controllers::s5::test
