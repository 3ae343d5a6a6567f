// SPDX-License-Identifier: MIT
#pragma once
// A WF 725/726 axis as a controller of the runtime (docs/wf725.md): a scenario's
//   controller: {device: wf725-726, parameters: axis-a.txt, programs: [progs.wf]}
// configures one axis from its machine data MD 1-50 (wf725_axes: scaling MD 19-21/49, MD 3,
// ramps, windows, backlash, rotary MD 18) and runs the modes, submodes and traversing programs of
// the digest's §6 on it, commanded by the PLC through the DB axis (wf725_interface.hpp) held as
// plain data words in the image (read_db_word / write_db_word, or `DB10 D 2.0` bits from `io:`).
// Errors are the module's (catalogues traversing, program_io, memory_admin, standard2): traversing
// errors in DR 4 with D 3.5, program-I/O errors in DW 40; acknowledged by data code 800C, the
// RESET bit, or cleared by the next valid start (self-acknowledging).
//
// Options (controller block keys): `axis` (A, B, C: the axis name and letter, default A),
// `module` (WF725A, WF725B, WF726A, WF726B, WF726C; default WF726A), `db` (DB number of the DB
// axis, default 10), `reference_speeds` ("rapid,reduced,slow" in mm/min, preset of data codes
// 8/9/A), `jog_feed` (mm/min, preset of data code 1C), `drift` (mV: the drive's input offset on X3;
// closed loop compensated by MD 35 / data code 10 in submode RUN, open loop a creep;
// wf725_controller_drift.cpp).
//
// I/O image: inputs byte 0 bits 0..5 = X7 E1..E6 (`x7_e1`..`x7_e6`); byte 1 bit 0/1
// `limit_minus_<axis>` / `limit_plus_<axis>` (the hard range-limit switch inputs, errors 15/16);
// outputs byte 0 bits 0..5 = X7 A1..A6 by MD 10; output byte 1: `in_position_<axis>`,
// `moving_<axis>`, `error_<axis>`, `drive_enable_<axis>` (the RF output); marker 0.0
// `device_error`; data area: the DB axis (48 words), `reference_cam_<axis>` names the cam
// (D 2.1 with MD 15 = 1, else X7 E<axis>).
// Thread: the cycle thread (Controller); read_db_word/write_db_word between cycles.

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/parameter_file.hpp"
#include "hil/controllers/s5/s5_interface_db.hpp"
#include "hil/controllers/s5/wf725_interface.hpp"
#include "hil/controllers/s5/wf725_machine_data.hpp"
#include "hil/controllers/s5/wf725_open_loop.hpp"
#include "hil/controllers/s5/wf725_program_store.hpp"
#include "hil/controllers/s5/wf725_split_drive.hpp"

namespace hil::controllers::s5 {

class Wf726Module;

struct Wf725Options {
  char axis = 'A';
  std::uint16_t db = 10;
  std::int64_t ref_speeds[3] = {0, 0, 0};  ///< 10^-2 mm/min (data codes 8, 9, A)
  std::int64_t jog_feed = 0;               ///< 10^-2 mm/min (data code 1C)
  char variant = 'A';                      ///< module variant: A incremental, B parallel absolute, C SSI (WF 726)
  int difference_cycles = 4;               ///< error 33 after this many jumps > MD 34 in a row (manual: 4 or 5)
  Wf725OpenLoopDrive drive;                ///< open loop: the drive behind X3 (open_loop_speed/_acceleration)
  bool split_monitoring_always = false;    ///< split drive: compare MD 29 without the enable bit D 2.3
  double drift_mv = 0.0;                   ///< the drive's input offset on X3, mV (key `drift`)
};

/// The S5 user data blocks beside the module: the PLC's DBs that the "Software Schale" FB copies
/// programs between (digest §5.5, errors 401/402), DB number -> words (DW 0..255). Each controller
/// owns one; `hilbridge emulate wf725` lends its endpoint's DB store to every axis of the module
/// (so the user DBs a PG tool writes over RK512 are the ones data code 44 reads, and persist).
using Wf725UserBlocks = std::map<std::uint8_t, std::vector<std::uint16_t>>;
inline constexpr std::size_t wf725_user_block_words = 256;  ///< DW 0..255 (what RK512 addresses)

/// One buffer of the automatic buffer (digest §6.2, errors B0-B3, 143-155): the PLC sets its length,
/// reloads blocks 1..length in ascending order without gaps; a completely loaded buffer can be
/// started; a buffer that ran is consumed (reloaded before it runs again).
struct Wf725Buffer {
  Wf725Program program;  ///< number = buffer number 1..6, the blocks loaded so far
  int length = 0;        ///< set by data code 48 (1..50), 0 = not set
  [[nodiscard]] bool complete() const noexcept {
    return length > 0 && static_cast<int>(program.blocks.size()) == length;
  }
};
inline constexpr int wf725_buffer_blocks = 50;

class Wf725Controller final : public Controller {
 public:
  Wf725Controller(LoadedParameters parameters, Wf725MachineData md, ControllerAxis axis, Duration cycle,
                  Wf725Options options);
  ~Wf725Controller() override {
    split_detach();
    store_->remove_user(store_user_);
  }
  Wf725Controller(const Wf725Controller&) = delete;
  Wf725Controller& operator=(const Wf725Controller&) = delete;

  /// Stores parsed programs (the scenario's `programs:`): 0 or the program-I/O error.
  [[nodiscard]] int store_program(Wf725Program p) { return store_->store(std::move(p)); }
  /// The program memory; the module's axes share one (docs/wf725.md, "Several axes").
  [[nodiscard]] const std::shared_ptr<Wf725ProgramStore>& program_store() const noexcept { return store_; }
  /// Uses `store` (non-null) as the program memory from now on: the axes of one module share
  /// their memory. Call between cycles while no program runs on this axis.
  void use_program_store(std::shared_ptr<Wf725ProgramStore> store) {
    store_->remove_user(store_user_);
    store_ = std::move(store);
    store_user_ = store_->add_user([this](int n) { return runs_stored_program(n); });
  }

  // ---- the module's axes (wf725_combined.cpp; docs/wf725.md "Combined programs") -------------
  /// The axis letter (A, B, C).
  [[nodiscard]] char axis_letter() const noexcept { return opt_.axis; }
  /// Called by Wf726Module::add (nullptr: the axis leaves its module). Between cycles only.
  void join_module(Wf726Module* module) noexcept { module_ = module; }
  [[nodiscard]] Wf726Module* module() const noexcept { return module_; }
  /// The master axis whose combined program moves this axis now (nullptr: none).
  [[nodiscard]] const Wf725Controller* master() const noexcept { return master_; }

  // ---- the PLC's view: the DB axis as plain words (S5InterfaceDb) ----------------------------
  [[nodiscard]] std::uint16_t read_db_word(std::uint16_t w) const noexcept { return db_.read_word(w); }
  void write_db_word(std::uint16_t w, std::uint16_t v) noexcept { db_.write_word(w, v); }
  [[nodiscard]] const S5DataBlock& interface_db() const noexcept { return db_.block(); }
  /// The DB axis as the data block in the image's data area (DW w = bytes 2w, 2w + 1): the
  /// runtime's `read_data_word(db, dw)` / `write_data_word` and so a scenario's `plc:` steps serve it.
  [[nodiscard]] std::span<const S5DataBlock> data_blocks() const noexcept override { return {&db_.block(), 1}; }

  [[nodiscard]] std::expected<BitAddress, std::string> resolve_bit(std::string_view text) const override;
  /// DB `db` = the DB axis (as the base class), any other DB number a user data block (created
  /// by its first write, at most DW 255): program input/output by data codes 44/45 reads and
  /// writes them (docs/wf725.md, "Program input/output").
  [[nodiscard]] std::expected<std::uint16_t, std::string> read_data_word(int db, int dw) const override;
  std::expected<void, std::string> write_data_word(int db, int dw, std::uint16_t value) override;
  /// Uses `blocks` (shared with the module's other axes; must outlive every later cycle) as the
  /// user data blocks; nullptr: the controller's own again.
  void use_user_blocks(Wf725UserBlocks* blocks) noexcept { user_blocks_ = blocks != nullptr ? blocks : &own_blocks_; }
  [[nodiscard]] Wf725UserBlocks& user_blocks() noexcept { return *user_blocks_; }

  // ---- machine data as the module holds them (data codes 50/51, the MD image of DB 1) ------
  /// MD n as its stored integer (MD 3, MD 22 in their 0.01 steps; the binary input format).
  [[nodiscard]] std::int32_t read_machine_data(int n) const noexcept;
  /// Writes MD n (stored integer): 0, or 121 (n outside 1..50) / 201 (not in mode machine-data
  /// input/output). MD that shape the axis apply at the next power-up (pending_md()).
  [[nodiscard]] int write_machine_data(int n, std::int32_t stored) noexcept;
  /// Whether the module is in mode machine-data input/output (D 0.10 accepted).
  [[nodiscard]] bool machine_data_mode() const noexcept {
    return mode_bits_ == (1U << (wf_db::bit_mode_machine_data - 8));
  }

  // ---- split drive (gantry) MD 27/29: wf725_split_drive.cpp, docs/wf725.md "Split drive" -----
  /// Makes `slave` (this module's axis B or C, the one MD 27 of this axis A names) follow this
  /// axis in the split-drive submodes. Error text (nothing coupled) when this is not axis A with
  /// MD 27 = 3 / 5 naming `slave`'s letter, either axis is open loop or rotary, or one is coupled.
  /// Construction time (before the first cycle); both must outlive each other's cycles.
  [[nodiscard]] std::expected<void, std::string> couple_split_drive(Wf725Controller& slave);
  /// Every run period, before this axis' update and after the master's: a coupled slave takes
  /// the master's set-point (plus the programmed shift); on any other axis nothing happens.
  void split_drive_period(const CycleTime& cycle) noexcept;
  /// The coupling this axis is master of (nullptr: none).
  [[nodiscard]] const Wf725SplitDrive* split_drive() const noexcept { return split_.get(); }
  /// Split-drive difference now: slave actual - master actual - commanded shift, µm (machine
  /// coordinates); nullopt when the axis is not coupled.
  [[nodiscard]] std::optional<double> split_difference_um() const noexcept;

  // ---- observation (tests, summary) ------------------------------------------------------------
  /// Actual value as the module shows it (program coordinates), µm (10^-3 degree).
  [[nodiscard]] double actual_um() const noexcept;
  [[nodiscard]] bool synchronized() const noexcept { return synced_; }
  [[nodiscard]] bool traversing() const noexcept { return traversing_; }
  [[nodiscard]] wf_db::Submode submode() const noexcept { return submode_; }
  [[nodiscard]] const Wf725MachineData& machine_data() const noexcept { return md_; }
  [[nodiscard]] const Wf725ProgramStore& programs() const noexcept { return *store_; }
  /// Buffer n (1..6) of the automatic buffer.
  [[nodiscard]] const Wf725Buffer& buffer(int n) const noexcept {
    return buffers_[static_cast<std::size_t>(std::clamp(n, 1, 6) - 1)];
  }
  /// Machine position latched at the last flying-measurement edge, µm.
  [[nodiscard]] std::optional<double> measured_um() const noexcept { return measured_um_; }
  /// Every M function output, in order.
  [[nodiscard]] const std::vector<int>& m_history() const noexcept { return m_history_; }
  /// Command position (program coordinates, µm) at each flying block change, in order.
  [[nodiscard]] const std::vector<double>& block_changes_um() const noexcept { return block_changes_um_; }
  /// Open loop (MD 4 = 3/4): every change of the speed level output during positionings, in
  /// order: the new level and the remaining distance (µm) at which the module switched.
  struct LevelChange {
    int level = 0;
    double remaining_um = 0.0;
  };
  [[nodiscard]] const std::vector<LevelChange>& level_changes() const noexcept { return ol_history_; }
  /// Open loop: the speed level output now (0..99; DL 4 in BCD, X3 = level x 100 mV).
  [[nodiscard]] int speed_level() const noexcept { return ol_.level; }
  [[nodiscard]] bool open_loop() const noexcept { return !md_.closed_loop(); }
  /// The set-point offset the drift and MD 35 give the axis, µm (docs/wf725.md "Drift"): closed loop
  /// drift / K_v - MD 35 (limited; at rest the following error reads its negative); open loop the
  /// creep of the drive at drift / 10 V x open_loop_speed since it was powered.
  [[nodiscard]] double drift_offset_um() const noexcept;
  /// MDs written in mode MD I/O that shape the axis: they apply at the next power-up.
  [[nodiscard]] const std::vector<int>& pending_md() const noexcept { return pending_md_; }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  enum class Job : std::uint8_t { none, jog, reference, move, program, clamping, slave };
  enum class RefPhase : std::uint8_t { rapid, reduced, slow };
  enum class Step : std::uint8_t {
    fetch,
    m_before,
    motion,
    m_after,
    dwell,
    wait_start,
    wait_enable,
    continuous,
    stopping,
    combined
  };
  enum class MState : std::uint8_t { idle, strobe, wait_release, timed };
  struct Frame {
    const Wf725Program* program = nullptr;
    std::size_t index = 0;
    int passes_left = 1;
  };

  void raise_wf(int code, TimePoint now, std::string_view context = {});
  void raise_io(int code, TimePoint now, std::string_view context = {}, std::string_view catalogue = "program_io");
  void clear_self_acknowledging() noexcept;
  [[nodiscard]] bool has_error_below_60() const noexcept;
  [[nodiscard]] bool has_error(int code) const noexcept;

  void handle_mode(TimePoint now);
  void handle_drive(TimePoint now);
  void handle_data_code(TimePoint now);
  /// The measuring-circuit checks of every cycle (docs/wf725.md, "Encoder faults"): 07, 08, 0B,
  /// 30-34 by their conditions and the encoder fault inputs, masked by MD 41 / MD 40.
  void encoder_cycle(TimePoint now);
  /// Raises an encoder error once (a measuring-circuit error < 60: drive off, position lost; 17
  /// as well when it strikes in a data mode with the drive enabled).
  void raise_encoder(int code, TimePoint now, std::string_view context);
  [[nodiscard]] bool encoder_input(int bit) const noexcept;
  /// The voltage checks 40-46 of every cycle (MD 41 S; docs/wf725.md "Voltage checks"), on the
  /// voltage fault inputs (input byte 3) and the command voltage.
  void voltage_cycle(TimePoint now);
  /// The command voltage on X3 now, mV (closed loop: feed / MD 3 x MD 23; open loop: level x 100).
  [[nodiscard]] double command_mv() const noexcept;
  /// The drift of the drive and its compensation MD 35 as the axis' set-point offset, every cycle
  /// (wf725_controller_drift.cpp); open loop: the creep of the drive since it was powered.
  void drift_cycle(TimePoint now);
  /// Data code 10 in submode RUN: the standstill following error into MD 35; the new MD 35 (µm).
  [[nodiscard]] std::int32_t compensate_drift(TimePoint now);
  /// Data codes 47/4A: writes a page of numbers into DW 30..38.
  void write_list(const std::vector<int>& numbers, int page);
  /// Data codes 44/45: program input from / output to a user data block (Software Schale).
  void program_input(int db, TimePoint now);
  void program_output(int program, int db, TimePoint now);
  /// Data codes 48/49: set the length of a buffer / reload blocks into it from a user data block.
  void buffer_length(int buffer, int length, TimePoint now);
  void buffer_reload(int buffer, int db, TimePoint now);
  /// 0 when `buffer` is one of this axis' pair (A: 1/2, B: 3/4, C: 5/6), else false.
  [[nodiscard]] bool own_buffer(int buffer) const noexcept;
  /// Start of the automatic buffer (submode 9) with the buffer of DW 5: B0, B1, B2, B3.
  bool start_buffer(TimePoint now);
  /// Runs buffer n from its first block (checks B1/B2/B3); false when it cannot.
  bool enter_buffer(int n, TimePoint now);
  /// After a finished block of a running buffer: M11/M12 change to the pair's other buffer.
  /// True when the block changed the buffer (or ended the job).
  bool buffer_change(TimePoint now);
  void handle_start(TimePoint now);
  void run_job(const CycleTime& cycle);
  void check_limits(TimePoint now);
  void write_status();

  void abort_job();
  // split drive (wf725_split_drive.cpp)
  /// At a start in a split submode: the slave in submode "0" (69/6B), ready (6A), MD 1/2/38/39 equal
  /// (6D), the axes together within MD 29 (25). False when the start is refused (error raised).
  bool split_start(TimePoint now);
  /// The master's cycle: engagement, the slave's errors (6A, 69/6B); the slave's cycle: split_compare.
  void split_cycle(TimePoint now);
  /// The slave's cycle: the MD 29 comparison (25 on both, the motion terminated), data code 30's value.
  void split_compare(TimePoint now);
  /// Data codes 30 (difference) / 31 (programmed shift): false when not a split-drive code.
  bool split_data_code(std::uint16_t code, std::int32_t p1, std::int32_t p2, TimePoint now, std::int32_t& result);
  [[nodiscard]] bool split_monitoring() const noexcept;
  void split_detach() noexcept;
  /// Whether this axis runs the stored program `number` (main or subprogram; not a buffer).
  [[nodiscard]] bool runs_stored_program(int number) const noexcept {
    const Wf725Program* p = store_->find(number);
    return p != nullptr && std::any_of(stack_.begin(), stack_.end(), [p](const Frame& f) { return f.program == p; });
  }
  /// Moves to machine position `target_mm` at `feed` (10^-2 mm/min), clamped to the armed
  /// pre-limits. False when the axis refused (error raised).
  /// `acceleration` > 0: the ramp of this move in mm/s^2 (an interpolation pair), else the axis'.
  bool go(double target_mm, std::int64_t feed, TimePoint now, motion::Direction dir = motion::Direction::shortest,
          double acceleration = 0.0);
  bool go_velocity(int direction, std::int64_t feed, TimePoint now);
  [[nodiscard]] bool armed() const noexcept { return synced_ || !md_.incremental(); }
  [[nodiscard]] double machine_mm() const noexcept;          ///< actual, machine coordinates
  [[nodiscard]] double machine_command_mm() const noexcept;  ///< command, machine coordinates
  [[nodiscard]] double to_axis(double machine_mm) const noexcept { return machine_mm - offset_mm_; }
  /// Axis position -> machine coordinates (on a rotary axis, into 0 .. MD 18).
  [[nodiscard]] double to_machine(double axis_mm) const noexcept;
  [[nodiscard]] bool cam() const noexcept;
  [[nodiscard]] bool fast_input(int e) const noexcept;
  [[nodiscard]] bool motion_done() const noexcept;
  [[nodiscard]] motion::Direction rotary_direction() const noexcept;

  // open loop (wf725_controller_open_loop.cpp): staged positioning by speed levels
  bool ol_go(double target_mm, std::int64_t level, TimePoint now, motion::Direction dir);
  bool ol_run(int direction, std::int64_t level, TimePoint now);
  void ol_cycle(TimePoint now);
  bool ol_command(int level, TimePoint now);
  void ol_stop();
  void ol_check_limits(TimePoint now);
  [[nodiscard]] bool ol_done() const noexcept;
  [[nodiscard]] double unwrapped_mm() const noexcept;  ///< actual axis position, not wrapped
  [[nodiscard]] Wf725OpenLoopStages ol_stages() const noexcept;
  [[nodiscard]] double ol_acceleration(int md) const noexcept;

  // programs
  bool start_program(TimePoint now, bool single_block);
  void program_cycle(const CycleTime& cycle);
  const Wf725Block* current_block() const noexcept;
  bool advance() noexcept;  ///< to the next block; false at the end of the main program
  bool begin_block(TimePoint now);
  bool begin_motion(TimePoint now);
  bool start_block_motion(TimePoint now);
  void finish_block();
  void continuous_cycle(TimePoint now);
  [[nodiscard]] double block_target_mm(const Wf725Block& b, bool absolute) const noexcept;
  [[nodiscard]] const Wf725Block* peek_next() const noexcept;
  bool flying_change(const CycleTime& cycle);
  void end_program();
  void output_m(int m, TimePoint now);
  void m_cycle(TimePoint now);

  // combined programs (wf725_combined.cpp)
  /// At the start of program `p` (master): every other axis its blocks name (subprograms
  /// included) exists on the module and is in traversing with submode "0" and no job: else 69 in
  /// that axis, 6B here (or 6B alone for an axis the module lacks); false then.
  bool check_slaves(const Wf725Program& p, TimePoint now);
  /// Whether the current block is combined: another axis' letter (1) or an interpolation pair (2).
  [[nodiscard]] int combined_kind(const Wf725Block& b) const noexcept;
  /// Starts the current combined block (or pair); false when it failed (error raised, job ended).
  bool begin_combined(TimePoint now);
  /// Step::combined: waits for the axes of the combined block; false while it runs or failed.
  bool combined_cycle(TimePoint now);
  /// Stops (`abort`) or releases the slaves this axis commands.
  void release_slaves(bool abort) noexcept;
  /// Slave side: whether the axis can take a block of a master's combined program.
  [[nodiscard]] bool slave_ready() const noexcept;
  /// Slave side: the machine target of block `b` in this axis' coordinates.
  [[nodiscard]] double combined_target(const Wf725Block& b, bool absolute) const noexcept;
  /// Slave side: moves to `target_mm` for `master` (Job::slave); false when the axis refused
  /// (its error raised here).
  bool slave_move(Wf725Controller& master, double target_mm, std::int64_t feed, double acceleration, TimePoint now);

  Wf725MachineData md_;
  Wf725Options opt_;
  std::shared_ptr<Wf725ProgramStore> store_;
  int store_user_ = -1;
  S5InterfaceDb db_;
  Wf725ProgramSyntax syntax_ = wf725_default_syntax();
  Wf725UserBlocks own_blocks_;
  Wf725UserBlocks* user_blocks_ = &own_blocks_;
  const profiles::ErrorCatalogue* traversing_cat_ = nullptr;
  const profiles::ErrorCatalogue* io_cat_ = nullptr;
  const profiles::ErrorCatalogue* admin_cat_ = nullptr;
  const profiles::ErrorCatalogue* standard2_cat_ = nullptr;
  std::optional<BitAddress> cam_bit_;

  bool traversing_ = false;
  std::uint8_t mode_bits_ = 0;  ///< active mode (DL 0 bits as accepted)
  wf_db::Submode submode_ = wf_db::Submode::none;
  bool synced_ = false;
  double offset_mm_ = 0.0;      ///< machine = axis + offset
  double zero_shift_mm_ = 0.0;  ///< program = machine + zero shift (G92 / G54)
  bool g92_active_ = false;
  bool g54_active_ = false;
  int tool_ = 0;
  std::array<std::int64_t, 21> offsets_um_{};
  int limit_side_ = 0;  ///< the running move was clamped to the pre-limit on this side
  int range_side_ = 0;  ///< the command position lies beyond MD 12 (-1) / MD 14 (+1)
  TimePoint last_now_{};
  bool drive_enabled_ = false;
  bool peh_ = false;
  bool positioning_ = false;  ///< a motion started since the PEH window was last reached
  std::vector<int> pending_md_;
  std::unique_ptr<Wf725SplitDrive> split_;   ///< master side of a split drive
  Wf725Controller* split_master_ = nullptr;  ///< slave side: the master (axis A)

  // jobs
  Job job_ = Job::none;
  int jog_dir_ = 0;
  RefPhase ref_ = RefPhase::rapid;
  int ref_dir_ = 0;
  int ref_bits_ = 0;
  double ref_target_axis_ = 0.0;
  std::int64_t ref_speeds_[3] = {0, 0, 0};
  std::int64_t jog_feed_ = 0;
  std::optional<std::int64_t> mdi_position_;
  bool mdi_incremental_ = false;
  std::int64_t mdi_feed_ = 0;
  double clamp_command_mm_ = 0.0;
  std::optional<double> measured_um_;
  bool powered_up_ = false;
  std::int64_t zero_mark_count_ = 0;  ///< zero marks passed (position_inc / MD 34), pulse monitor 08
  bool zero_mark_known_ = false;
  int jumps_ = 0;                      ///< successive position jumps > MD 34 (absolute, 33)
  std::int64_t pulse_difference_ = 0;  ///< pulses lost (< 0) since power-up (data code 4)
  std::int64_t last_inc_ = 0;
  std::int32_t control_mv_ = 0;  ///< submode control: voltage (data code 1D)
  double creep_mm_ = 0.0;        ///< open loop: how far the drift moved the drive since it was powered
  TimePoint drift_at_{};         ///< the cycle creep_mm_ was integrated to

  // program
  std::vector<Frame> stack_;
  Step step_ = Step::fetch;
  bool single_ = false;     ///< one block per start (single step, automatic single step)
  bool absolute_ = true;    ///< modal G90 / G91
  std::int64_t feed_ = 0;   ///< modal F
  double target_mm_ = 0.0;  ///< machine target of the block's motion
  int change_group_ = 0;    ///< 46 / 47: the block's G2x / G7x block-change tolerance, else 0
  bool flying_in_ = false;  ///< the running block was entered by a flying change
  TimePoint dwell_end_{};
  bool m0_pending_ = false;
  int after_m_ = -1;  ///< M output after the motion (MD 9 = 3)
  int running_program_ = 0;
  int running_buffer_ = 0;  ///< 1..6 while the automatic buffer runs
  std::array<Wf725Buffer, 6> buffers_{};
  int running_block_ = 0;
  bool continuous_measure_ = false;  ///< G68/G69 block waits for the fast-input edge
  int continuous_input_ = 0;
  bool g99_wait_ = false;

  // open loop
  struct OpenLoop {
    bool active = false;       ///< a speed level runs or the axis brakes after speed 0
    bool positioning = false;  ///< staged positioning to `target` (else an endless run: jog, reference)
    int dir = 0;
    int programmed = 0;
    int level = 0;
    double target = 0.0;  ///< unwrapped axis position, mm
    bool zero = false;    ///< speed 0 output (MD 48 reached); MD 30 runs from `zero_at`
    TimePoint zero_at{};
    bool peh = false;  ///< the PEH window MD 33 was reached after speed 0: leaving it is 21
  } ol_;
  std::vector<LevelChange> ol_history_;

  // M output
  MState m_state_ = MState::idle;
  int m_ = 0;
  TimePoint m_until_{};
  std::vector<int> m_history_;
  std::vector<double> block_changes_um_;

  // combined programs
  Wf726Module* module_ = nullptr;
  Wf725Controller* master_ = nullptr;                ///< slave: the master moving this axis
  std::array<Wf725Controller*, 2> combined_axes_{};  ///< master: the axes of the running combined block
  int combined_blocks_ = 0;                          ///< master: blocks the running combined step takes (1, 2)
  bool combined_done_ = false;                       ///< master: the motion of the combined step ended
  std::vector<int> combined_m_;                      ///< master: M functions output after the combined motion
};

/// Registers `wf725-726` in `registry` (the module model; replaces a factory of that name).
void register_wf725(ControllerRegistry& registry);

/// Whether a `controller:` block asks for the module model (programs, or one of its keys `db`,
/// `module`, `reference_speeds`, `jog_feed`) rather than the parameter-only controller, whose
/// axis the scenario commands itself (docs/controllers.md).
[[nodiscard]] bool wf725_wants_module(const ControllerSpec& spec) noexcept;

}  // namespace hil::controllers::s5
