// SPDX-License-Identifier: MIT
#pragma once
// One IP247 axis: the operating modes of manual §4 (digest ip247.md §4.3-4.13) as a step function
// on the IP247 step planner (exponential ramp, exact pulse positions).
//
// Commands arrive as operating commands (BA + Start/Stop/Vorwärts/Rückwärts/Übernahme + the byte,
// word and double-word parameters of the interface DB). Every command first acknowledges the
// latched error; a command while the axis is running aborts it with error 2 (except Stop, BA4,
// jog switching and the takeover of a waiting program); an accepted job sets "running" (attribute
// bit 7 clear) until it ends. Errors carry the module's numbers (hil::stepdir::Ip247Error);
// 1..9 are warnings. The machine data configure the planner: pulses/rev and gear give the
// resolution, fmax/fss/a the ramp, and every move runs at its own speed (jog 1/2, incremental,
// reference, the program's F, G00 = vmax) converted to a pulse frequency.
//
// Inputs are raw levels (limit polarity from the MD applies here); `step(now, period)` advances
// the axis by one module cycle and appends the step/dir edges of the window to `edges`.
// Thread: the module cycle only. Never throws, no allocation in step() except `edges` and traces.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/s5/ip247_coordinates.hpp"
#include "hil/controllers/s5/ip247_interpreter.hpp"
#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_program_store.hpp"
#include "hil/gpio/edge.hpp"
#include "hil/stepdir/step_planner.hpp"

namespace hil::controllers::s5 {

enum class Ip247Command : std::uint8_t { start, stop, forward, backward, takeover };

struct Ip247Job {
  int ba = 0;
  Ip247Command command = Ip247Command::start;
  int byte_param = 0;      ///< BA5: 0 approach / else set; BA8/9/10: program number
  std::int32_t speed = 0;  ///< BA1/2/6/7 word parameter, unit/min; 0 = MD speed
  std::int64_t value = 0;  ///< BA6 target, BA7 distance, BA12/13 coordinate, BA15 offset (BU)
};

/// Raw input levels of one axis (X7 and the power-section connector).
struct Ip247Inputs {
  bool limit_start = false;    ///< E ANF (level as wired; NC: 1 = not actuated)
  bool limit_end = false;      ///< E END
  bool reference = false;      ///< E BERO (cam), NO, 1 = on the cam
  bool external_stop = false;  ///< E START-N/STOP: 0->1 = stop, 1->0 = start enable
  bool ready = true;           ///< BB
};

/// Attribute byte bits (manual §2.7, digest §4.1).
namespace ip247_attr {
inline constexpr std::uint8_t position_reached = 0x04;
inline constexpr std::uint8_t synchronous = 0x08;
inline constexpr std::uint8_t teach_in = 0x10;
inline constexpr std::uint8_t reference_missing = 0x20;
inline constexpr std::uint8_t md_missing = 0x40;
inline constexpr std::uint8_t finished = 0x80;
}  // namespace ip247_attr

class Ip247Axis {
 public:
  Ip247Axis(Ip247ProgramStore& store, int axis_number, Ip247InterpreterOptions io = {});

  /// BA20: the checked MD set configures the axis (error 15 + MD error on rejection; the set's
  /// error byte is the return value). Offsets are cleared; the reference point is kept only if
  /// the reference-relevant MD are unchanged.
  stepdir::Ip247MdError load_machine_data(const Ip247MachineData& md, int sysid_module);
  /// BA21. The pulse position and the deleted set are kept, so a following BA20 with unchanged
  /// reference-relevant MD keeps the reference point (§2.5.1: MD are replaced by delete + write).
  stepdir::Ip247Error delete_machine_data();
  /// A faulty MD set was transferred (BA20 refused by the check): attribute 40h "MD missing"
  /// clears, as on the module, but motion commands still get error 14 until BA21 + a good BA20.
  void set_faulty_machine_data(bool present) noexcept { faulty_md_ = present; }
  /// Latches a module error the module raises for this axis outside an operating command (a data
  /// job on the axis tile: 15, 46, 13 ...). Acknowledged by the next operating command.
  void report(stepdir::Ip247Error e) noexcept { error_ = static_cast<int>(e); }
  /// An operating command (PG or AG).
  void command(const Ip247Job& job);
  /// One module cycle.
  void step(std::int64_t now_ns, std::int64_t period_ns, const Ip247Inputs& in, std::vector<gpio::Edge>* edges);
  /// BB as read before this cycle's jobs (a controller that hands the jobs over before step());
  /// step() reads it too. A motion job with BB low is refused with error 53.
  void read_bb(bool ready) noexcept { bb_ = ready; }
  /// Restart after power failure (§7.3.3): the job is dropped, reference lost, BA4, message 8,
  /// actual value = reference coordinate; offsets and MD kept with battery, else everything lost.
  void power_restart(bool battery_ok);
  /// BA17 on this axis (state ready only).
  void clear_error();

  // Observation (FB164 RMLD / BA66 / BA71 / BA73).
  [[nodiscard]] std::int64_t actual() const noexcept;     ///< displayed actual value (BU)
  [[nodiscard]] std::int64_t remaining() const noexcept;  ///< remaining distance (BU)
  [[nodiscard]] std::uint8_t attributes() const noexcept;
  [[nodiscard]] int error() const noexcept { return error_; }
  [[nodiscard]] int m_output() const noexcept;
  [[nodiscard]] int ba() const noexcept { return ba_; }
  [[nodiscard]] bool running() const noexcept { return running_; }
  [[nodiscard]] bool position_reached() const noexcept { return pe_; }
  [[nodiscard]] bool referenced() const noexcept { return referenced_; }
  [[nodiscard]] bool teach_in() const noexcept { return teach_in_; }
  /// A program waits for a takeover (M00 halt point, single block).
  [[nodiscard]] bool waits_for_takeover() const noexcept {
    return phase_ == Phase::program && prog_ == ProgState::wait_takeover;
  }
  /// An interrupted program waits for continuation (error 65).
  [[nodiscard]] bool interrupted() const noexcept {
    return phase_ == Phase::program && prog_ == ProgState::interrupted;
  }
  [[nodiscard]] const Ip247Offsets& offsets() const noexcept { return off_; }
  [[nodiscard]] const std::optional<Ip247MachineData>& machine_data() const noexcept { return md_; }
  [[nodiscard]] const stepdir::StepPlanner* planner() const noexcept { return planner_.get(); }
  /// Internal position p (BU, unwrapped).
  [[nodiscard]] std::int64_t internal_position() const noexcept;
  /// Every change of the M-function output while a program runs, and the takeovers consumed.
  [[nodiscard]] const std::vector<int>& m_history() const noexcept { return m_history_; }
  [[nodiscard]] int takeovers() const noexcept { return takeovers_; }
  /// The program being recorded by teach-in (text so far).
  [[nodiscard]] const Ip247Program& teach_program() const noexcept { return teach_; }
  [[nodiscard]] const Ip247Interpreter& interpreter() const noexcept { return interp_; }

 private:
  enum class Phase : std::uint8_t {
    idle,
    jog,
    move,       ///< BA6/BA7
    reference,  ///< BA5 approach
    program,    ///< BA8/BA9
  };
  enum class ProgState : std::uint8_t { fetch, wait_takeover, wait_start, motion, dwell, interrupted };
  enum class RefPhase : std::uint8_t { away, search, back, creep, leave };

  enum class Resume : std::uint8_t { fetch, action, motion };
  void raise(stepdir::Ip247Error e);
  [[nodiscard]] bool busy() const noexcept;
  void go(std::int64_t target_pulses, double f_hz);
  void abort_job();
  void finish_job();
  void start_move(std::int64_t target_p, double speed, bool check_clamp);
  bool start_program(const Ip247Job& job);
  void program_step(std::int64_t now_ns);
  void execute(const Ip247Action& a, std::int64_t now_ns);
  void interrupt();
  void reference_step(const Ip247Inputs& in);
  void teach_store();
  void set_m(int m);
  [[nodiscard]] bool actuated_start(const Ip247Inputs& in) const noexcept;
  [[nodiscard]] bool actuated_end(const Ip247Inputs& in) const noexcept;
  [[nodiscard]] double clamp_speed(std::int32_t v, std::int32_t md_speed, bool& clamped) const noexcept;
  [[nodiscard]] std::int64_t range() const noexcept;

  Ip247ProgramStore& store_;
  int axis_;
  std::optional<Ip247MachineData> md_;
  std::optional<Ip247MachineData> deleted_md_;  ///< the set BA21 removed (reference retention)
  std::int64_t deleted_pulses_ = 0;             ///< the pulse position when it was removed
  bool faulty_md_ = false;
  Ip247Kinematics kin_;
  std::shared_ptr<const stepdir::Ip247Ramp> ramp_;
  std::unique_ptr<stepdir::StepPlanner> planner_;
  Ip247Interpreter interp_;
  Ip247Offsets off_;

  int ba_ = 4;
  bool running_ = false;
  bool pe_ = false;
  bool referenced_ = false;
  bool sync_ = false;
  int error_ = 0;
  Phase phase_ = Phase::idle;
  int jog_dir_ = 0;
  std::optional<Ip247Job> pending_jog_;
  std::int64_t target_p_ = 0;  ///< target of the current move (internal BU)
  bool has_target_ = false;
  int lock_dir_ = 0;  ///< direction locked after a limit-switch overrun
  Ip247Inputs prev_in_{};
  bool first_step_ = true;
  bool bb_ = true;         ///< BB level last read (Ip247Inputs::ready)
  bool ext_wait_ = false;  ///< job held by the external start/stop input (message 6)
  std::int64_t now_ = 0;
  std::vector<gpio::Edge> scratch_;

  // program
  ProgState prog_ = ProgState::fetch;
  int program_ = -1;
  bool single_block_ = false;
  Ip247Action action_{};
  std::optional<Ip247Action> next_;  ///< G10 lookahead (the block joined without stopping)
  std::int64_t transition_p_ = 0;    ///< where the flying change switches to `next_`
  std::int64_t dwell_end_ = 0;
  Resume resume_ = Resume::fetch;
  double held_f_ = 0.0;  ///< frequency of a move held by the external start/stop input
  std::int64_t held_target_ = 0;
  std::int64_t ref_pattern_base_ = 0;
  int m_ = 2;
  std::vector<int> m_history_;
  int takeovers_ = 0;

  // reference approach
  RefPhase ref_ = RefPhase::away;
  bool ref_seen_cam_ = false;
  std::int64_t single_steps_ = 0;

  // teach-in
  bool teach_in_ = false;
  Ip247Program teach_;
};

}  // namespace hil::controllers::s5
