// SPDX-License-Identifier: MIT
#pragma once
// IP247 traversing-program interpreter (manual §2.6, §4.3.1-4.3.3; digest ip247.md §3, §4.9).
// Pure and clock-free: it walks the program text and hands the axis one action at a time
// (motion, dwell, end, fault), applying switchings and offsets on the way (G25-G27, G40/G43/G44,
// G53-G57, G70/G71, G90/G91), expanding loops (G24/G20) and subprogram calls (L), and carrying the
// M-function output (M255 before the first M, output at the start of a motion/dwell block, held;
// M02 after the end) and the M00 halt points (a halt before the next motion/dwell; a standalone
// M00 is a zero-length motion; in single block (BA9) every motion/dwell halts and M00 adds none).
// G10 blocks are flagged `flying`; the structural G10 rules (next block a motion in the same
// direction, no switching/dwell/M02 in between) give error 52 (rotary shortest-path chains 47);
// the kinematic ones (braking distance, reaching the speed) are checked by the axis.
//
// Errors are the module's numbers (hil::stepdir::Ip247Error). `next()` interprets at most
// `budget` blocks per call (the module interprets a few blocks per cycle), so a loop of
// switchings never hangs the cycle.

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "hil/controllers/s5/ip247_coordinates.hpp"
#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/stepdir/ip247_error.hpp"

namespace hil::controllers::s5 {

inline constexpr int ip247_m_none = 255;  ///< output before the first M of a run
inline constexpr int ip247_max_nesting = 5;

struct Ip247Action {
  enum class Kind : std::uint8_t { pending, motion, dwell, end, fault };
  Kind kind = Kind::pending;
  int program = 0;
  int block = 0;  ///< N
  int line = 0;
  bool halt_before = false;  ///< wait for a takeover (M00, single block) before executing it
  int m_output = -1;         ///< M output from the start of this action; -1 = unchanged
  std::int64_t target = 0;   ///< motion: internal target p (BU, unwrapped on rotary axes)
  double speed = 0.0;        ///< motion: unit/min of the axis
  bool rapid = false;        ///< G00: vmax
  bool reference = false;    ///< G74: the known reference point at the incremental speed
  bool flying = false;       ///< G10: join the next motion without stopping
  bool zero_length = false;  ///< standalone M00
  std::int64_t dwell_ms = 0;
  stepdir::Ip247Error error = stepdir::Ip247Error::none;
};

struct Ip247InterpreterOptions {
  /// G24 Fn: n passes (true, default) or n repetitions after the first pass (the manual uses
  /// both words; docs/ip247.md).
  bool loop_count_is_passes = true;
  /// Blocks interpreted per next() call.
  std::size_t budget = 64;
};

/// (program, N, M output after the block) for every block interpreted; for tests and traces.
struct Ip247TraceEntry {
  int program = 0;
  int block = 0;
  int m_output = 0;
  friend bool operator==(const Ip247TraceEntry&, const Ip247TraceEntry&) = default;
};

class Ip247Interpreter {
 public:
  using Lookup = std::function<const Ip247Program*(int number)>;
  explicit Ip247Interpreter(Lookup programs, Ip247InterpreterOptions o = {}) : lookup_(std::move(programs)), o_(o) {}

  /// Start `program` from its first block; `from` = the internal position (BU) the first
  /// relative move starts at. Defaults G25, G90 and the MD unit. Error 13 if it does not exist.
  stepdir::Ip247Error start(int program, const Ip247MachineData& md, std::int64_t from, bool single_block);
  /// The next action. Offsets are applied to `off` as the blocks are interpreted.
  Ip247Action next(Ip247Offsets& off);
  /// Abort (program offsets are NOT removed: BA14 does that).
  void abort() noexcept { running_ = false; }
  /// Single block on/off (BA9 <-> BA8 continuation).
  void set_single_block(bool on) noexcept { single_block_ = on; }
  /// The position the next relative move starts from (after an interruption the axis sets it).
  void set_from(std::int64_t p) noexcept { from_ = p; }

  [[nodiscard]] bool running() const noexcept { return running_; }
  [[nodiscard]] int m_output() const noexcept { return m_out_; }
  [[nodiscard]] int program() const noexcept { return depth_ > 0 ? stack_[0].prog->number : 0; }
  /// Trace of interpreted blocks (off by default; `enable_trace(true)` records).
  void enable_trace(bool on) { trace_on_ = on; }
  [[nodiscard]] const std::vector<Ip247TraceEntry>& trace() const noexcept { return trace_; }
  /// Blocks interpreted since construction (for the cost per block of bench_controllers_s5).
  [[nodiscard]] std::uint64_t blocks_interpreted() const noexcept { return blocks_; }

 private:
  struct Frame {
    const Ip247Program* prog = nullptr;
    std::size_t pc = 0;          ///< next block index
    bool loop = false;           ///< loop frame (else call frame)
    std::size_t loop_start = 0;  ///< index of the G24 block
    std::int32_t remaining = 0;  ///< passes left; 0 = endless
    bool moved = false;          ///< a motion or dwell in the current pass (endless loops need one)
  };
  Ip247Action fail(stepdir::Ip247Error e, const Ip247Block& b);
  Ip247Action motion(const Ip247Block& b, Ip247Offsets& off);
  bool to_axis_unit(std::int64_t& v) const noexcept;
  void mark_moved() noexcept;
  void traced(const Ip247Block& b);
  const Ip247Program& current() const noexcept;

  Lookup lookup_;
  Ip247InterpreterOptions o_;
  const Ip247MachineData* md_ = nullptr;
  Ip247Kinematics kin_;
  std::array<Frame, ip247_max_nesting + 2> stack_{};
  int depth_ = 0;  ///< frames in use (main = 1)
  bool running_ = false;
  bool single_block_ = false;
  bool absolute_ = true;
  Ip247Rotary rotary_ = Ip247Rotary::shortest;
  bool inch_ = false;          ///< program unit 0.1 inch (G70)
  bool halt_pending_ = false;  ///< an M00 was executed: halt before the next motion/dwell
  bool flying_prev_ = false;   ///< the previous action was a G10 motion
  int flying_dir_ = 0;
  std::int64_t from_ = 0;
  int m_out_ = 2;
  bool trace_on_ = false;
  std::uint64_t blocks_ = 0;
  std::vector<Ip247TraceEntry> trace_;
};

}  // namespace hil::controllers::s5
