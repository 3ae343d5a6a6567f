// SPDX-License-Identifier: MIT
#pragma once
// The Rexroth CLM1.4 as a step function on the motion core (manual §5-§7, digest clm14.md §3-§7):
// program memory (3000 lines), parameters, variables V000-V999, counters, markers and I/O,
// 5 NC tasks executing one instruction each per NC cycle in the order 1..5, the logic task,
// the modes Parameter / Manual / Automatic from the system inputs, Start, Immediate Stop,
// E-Stop, drive enable / brake, errors with the device's numbers and the restart vector.
//
// Thread: every member on the controller's cycle thread. cycle() never blocks and never throws;
// configuration calls return std::expected. Time comes only from the caller (`now`), so a run is
// deterministic on virtual time.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <expected>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hil/controllers/clm14/address.hpp"
#include "hil/controllers/clm14/analog_input.hpp"
#include "hil/controllers/clm14/axis_port.hpp"
#include "hil/controllers/clm14/homing.hpp"
#include "hil/controllers/clm14/instruction.hpp"
#include "hil/controllers/clm14/logic_task.hpp"
#include "hil/controllers/clm14/master_encoder.hpp"
#include "hil/controllers/clm14/settings.hpp"
#include "hil/core/clock.hpp"
#include "hil/motion/coupling.hpp"
#include "hil/motion/master.hpp"

namespace hil::controllers::clm14 {

enum class Mode : std::uint8_t { parameter, manual, automatic };
/// Program run state of tasks 1, 2, 4, 5 (manual §7.2).
enum class RunState : std::uint8_t { idle, running, stopped };

/// The unit of the Ax16 windows "ww" (manual: "units not stated"; docs/clm14.md).
enum class WheelWindowUnit : std::uint8_t {
  iu,       ///< IU of wheel-motor difference within one wheel revolution (C002 / C006 IU of wheel travel)
  percent,  ///< % of the wheel's feed constant (C002 / C006) within one wheel revolution
};

/// Decisions where the manual lost a detail (docs/clm14.md lists each); defaults as documented.
struct Options {
  Duration logic_period{std::chrono::milliseconds(4)};   ///< §6: "minimum cycle 4 ms"
  int mat_cycles_add = 1;                                ///< MAT + / -: cycles until the task proceeds
  int mat_cycles_mul = 2;                                ///< MAT * and /
  Duration brake_delay{std::chrono::milliseconds(200)};  ///< §9.1: brake released 200 ms after enable
  /// CID Vnnn m ±value: mode 0 = set, 1 = add (manual: "changes the data in a variable", mode lost).
  bool cid_mode1_adds = true;
  /// MLO: true = the bit toggles each time the processed length passes the programmed length;
  /// false = it is set each time (the program clears it). The manual: "set/clear a bit".
  bool mlo_toggles = true;
  /// HOM and the Ax23 homing input: false = the CLM's own homing options 1-4 against the home
  /// switch and the encoder marker (homing.hpp); true = the drive's homing (hil::Drive request,
  /// e.g. a CiA 402 method with the switch wired to the drive), after which the position is Ax25.
  bool drive_homing = false;
  /// The marker pulse of axes 1..4 (homing options 1 and 2).
  std::array<MarkerSource, 4> markers{};
  /// Ax16 window unit (measuring-wheel modes 3/4).
  WheelWindowUnit wheel_window = WheelWindowUnit::iu;
  /// Measuring-wheel modes 3/4: the motor target takes the wheel-motor difference through a
  /// first-order lag of this many NC cycles (the wheel loop's gain: stable while the wheel's
  /// signal lags the motor by a few cycles - its compliance, the drive's own lag). 1 = at once.
  int wheel_correction_cycles = 16;
  /// B015 interrupt vector with p = 1 (moves interrupted): FOL mode-2 slaves ramp out, to be
  /// re-synchronised by the next FOL (or Start after a stop). false: they keep following.
  bool fol2_stops_at_interrupt = true;
};

/// LMR (manual §5.7, vector 37): the raster distance (material from the previous mark at the
/// tool to the next mark at the light barrier) and the offset distance (material from the mark
/// seen at the barrier to the cut) from the light-barrier offset `barrier` (> 0: the barrier sits
/// before the material entry, i.e. upstream of the tool; < 0: after it), the mark distance and
/// the cut's offset behind the mark. barrier 100, marks 1000, offset 300: 900 / 400 before the
/// entry, 1100 / 200 after it.
struct LmrGeometry {
  double raster = 0.0;
  double offset = 0.0;
};
[[nodiscard]] constexpr LmrGeometry lmr_geometry(double mark_distance, double offset, double barrier) noexcept {
  return {mark_distance - barrier, offset + barrier};
}

/// Slave increments per master increment for `factor` × (slave increments per IU) / (master
/// increments per IU), each "increments per IU" given as pulses × 4 per feed constant (in
/// 1e-5 IU), the factor in millionths: exact when it fits GearRatio (|num|, den <= 2^31), else
/// the nearest fraction that does (continued fraction; docs/clm14.md).
/// `master_factor` multiplies the master's feed constant (FAK 5 on master encoder 1).
[[nodiscard]] motion::GearRatio clm_gear_ratio(Micro factor, std::int64_t slave_pulses, std::int64_t slave_feed_e5,
                                               std::int64_t master_pulses, std::int64_t master_feed_e5,
                                               Micro master_factor = micro_one) noexcept;

/// One task's visible state (status 02/08/39, V002-V006).
struct TaskView {
  bool used = false;
  bool active = false;
  int pc = 0;       ///< current instruction
  int main_pc = 0;  ///< instruction of the main program (caller of the outermost JSR + 1), = pc outside subroutines
  int depth = 0;    ///< subroutine levels
};

class Controller {
 public:
  static constexpr int program_lines = 3000;
  static constexpr int logic_lines = 1000;
  static constexpr int max_stack = 127;

  explicit Controller(Options options = {});

  // ---- memory (the device's battery-buffered RAM) -----------------------------------------
  /// Store one program line "MNE operands" (any mode, like the serial `#N` telegram). A COU/BAC
  /// offset is applied to the line's counter now and the stored offset reset (manual §5.7 COU).
  /// On error nothing changes; the error is the device's code for the fault (0A, 16, 1D, 0E).
  std::expected<void, ProgramError> store_line(int line, std::string_view text);
  /// Replace the whole program (lines not listed become NOP). All or nothing.
  std::expected<void, ProgramError> load_program(const std::vector<std::pair<int, std::string>>& lines);
  [[nodiscard]] const std::string& line_text(int line) const { return text_.at(static_cast<std::size_t>(line)); }
  /// Logic-task line (compiled on power-up and on leaving Parameter mode). Outside Parameter
  /// mode a change is error 39 "Logic Prg. Lost".
  void store_logic_line(int line, std::string text);
  [[nodiscard]] const std::string& logic_line(int line) const { return logic_text_.at(static_cast<std::size_t>(line)); }
  /// The parameter set (read at power-up and on leaving Parameter mode).
  void set_parameters(ParameterLookup lookup) { parameters_ = std::move(lookup); }
  /// Extra check of the whole set run first (the profile's field ranges); its error is error 02.
  void set_parameter_validator(std::function<std::expected<void, ProgramError>()> v) { validator_ = std::move(v); }
  /// Called with new settings before the axes are checked (an owner may rebuild its axes here).
  void on_settings(std::function<void(const Settings&)> f) { on_settings_ = std::move(f); }
  /// Attach axis 1..4 (not owned). Axes without a port cannot be enabled in B000.
  void attach_axis(int axis, AxisPort* port);
  /// Attach master encoder 1 (not owned; nullptr = none). Without it, FOL from master encoder 1,
  /// VEO source 5, AEO and the flying cutoff stop the program with 0A naming the encoder.
  void attach_master_encoder(MasterEncoderPort* port);
  /// Attach master encoder 2 (C004-C006; not owned; nullptr = none): FUN's channel 6 (V042 /
  /// V043) and VEO source 6 [decided]. Without it they stop the program with 0A naming it.
  void attach_master_encoder2(MasterEncoderPort* port);

  // ---- run ---------------------------------------------------------------------------------
  /// Power-up sequence (§7.4): parameter check (02), logic compile (38), task 3 start.
  void power_up(TimePoint now);
  /// One NC cycle: inputs -> modes/safety -> tasks 1..5 -> logic task -> outputs.
  void cycle(TimePoint now);
  [[nodiscard]] Image& image() noexcept { return image_; }
  [[nodiscard]] const Image& image() const noexcept { return image_; }

  // ---- interface commands (§9.2 "!") -------------------------------------------------------
  /// !START: start/resume in Automatic (false = not in Automatic).
  bool command_start();
  /// !STOP: immediate stop; afterwards only !START resumes.
  void command_stop();
  /// !CLEAR: acknowledge the error.
  void command_clear();
  /// !CL0 (Manual): the flying cutoff's next entry into Automatic starts task 1 at 0000 instead
  /// of before the last length instruction (§7.12, A138). False outside Manual.
  bool command_start_0000();
  /// !CCLVAR0019: clear the hour counter V019.
  void clear_hour_counter() { hours_ms_ = 0.0; }
  /// !MxON / !MxOFF.
  void set_axis_software_enable(int axis, bool on);

  // ---- state ---------------------------------------------------------------------------------
  [[nodiscard]] Mode mode() const noexcept { return mode_; }
  [[nodiscard]] RunState run_state() const noexcept { return run_; }
  /// Current error code (0 = none).
  [[nodiscard]] int error() const noexcept { return error_; }
  /// What caused the error: "NC line 0012: ..." (empty when none).
  [[nodiscard]] const std::string& error_message() const noexcept { return error_message_; }
  /// Status 60: the item in error per kind (0 parameter, 1 NC line, 2 logic line, 3 variable), "" if none.
  [[nodiscard]] std::string error_item(int kind) const;
  [[nodiscard]] Micro variable(int n) const;
  /// Serial/host write of V600..V999 (false: not writable).
  bool set_variable(int n, Micro v);
  /// Counter of the COU/BAC on `line`; nullopt when the line holds none.
  struct CounterView {
    int count = 0;
    int preset = 0;
  };
  [[nodiscard]] std::optional<CounterView> counter(int line) const;
  [[nodiscard]] TaskView task(int t) const;  ///< t = 1..5
  /// Axis position in CLM coordinates (IU) and whether the axis is homed.
  [[nodiscard]] double position(int axis) const;
  [[nodiscard]] double following_error(int axis) const;
  [[nodiscard]] double velocity(int axis) const;
  [[nodiscard]] bool homed(int axis) const;
  /// Position latched by the last SRM mark (status 41).
  [[nodiscard]] double latched_position(int axis) const;
  /// Status 53 text set by TXT 1 (empty when none); status 63 lines (TXT 0).
  [[nodiscard]] const std::string& status_text() const noexcept { return txt53_; }
  [[nodiscard]] const std::array<std::string, 4>& text_lines() const noexcept { return txt63_; }
  [[nodiscard]] bool restart_possible() const noexcept { return restart_.valid; }
  [[nodiscard]] const Settings& settings() const noexcept { return settings_; }
  [[nodiscard]] std::uint64_t cycles() const noexcept { return cycle_count_; }
  [[nodiscard]] Duration cycle_time() const;
  /// Time of the last cycle.
  [[nodiscard]] TimePoint now() const noexcept { return now_; }
  [[nodiscard]] bool powered() const noexcept { return powered_; }
  /// Master encoder 1: travel in IU (C002 × FAK 5 per C000 × 4 counts) and velocity (V011).
  [[nodiscard]] double master_position() const noexcept;
  [[nodiscard]] double master_velocity() const noexcept;
  /// The motor encoder's position of axis 1 / 2 in CLM coordinates (IU): V047 / V048 and
  /// status 09's n in measuring-wheel mode; = position(axis) when the wheel never closed the loop.
  [[nodiscard]] double motor_position(int axis) const;
  /// Whether the measuring wheel of axis 1 / 2 closes the loop this cycle (Ax00 mode 3/4,
  /// Automatic, the Ax31 input).
  [[nodiscard]] bool wheel_active(int axis) const noexcept;
  /// Master encoder 2: travel in IU (C006 per C004 × 4 counts) and velocity (IU/s, 8 NC cycles).
  [[nodiscard]] double master2_position() const noexcept;
  [[nodiscard]] double master2_velocity() const noexcept;
  /// Flying cutoff: synchronisations (cuts) so far, and the material point (ME1 IU) of the last.
  [[nodiscard]] std::uint64_t cuts() const noexcept { return cut_.cuts; }
  [[nodiscard]] double last_cut_point() const noexcept;
  /// Whether axis `axis` follows a master now (FOL or the flying cutoff's synchronous run).
  [[nodiscard]] bool coupled(int axis) const noexcept;
  /// Flying cutoff length counters (status 54, §7.12): 1 = material (all master encoder 1 travel
  /// in Manual and Automatic), 2 = product (travel in Automatic while the cut is not inhibited), IU.
  [[nodiscard]] double length_counter(int which) const noexcept;
  /// !CLL1 / !CLL2: clear the material / product length counter.
  void clear_length_counter(int which) noexcept;
  /// Flying cutoff test mode (A100 field 4): the CTA's speed keys, step 0..31 = 0..A106 in 31
  /// equal steps (clamped). Set to 0 on Automatic -> Manual.
  void set_test_speed_step(int step) noexcept { test_step_ = std::clamp(step, 0, test_speed_steps - 1); }
  [[nodiscard]] int test_speed_step() const noexcept { return test_step_; }
  static constexpr int test_speed_steps = 32;
  /// Analog inputs AE1..AE4 (X5/X7, ±10 V; status 49 / 45), in mV, clamped to ±10000. The
  /// owner sets them like the hardware (emulator console, scenario stimuli); 0 until set. The
  /// model samples them once per NC cycle into the B017 moving average (analog_input.hpp), which
  /// V007..V010 (±1) and the override sources 1..4 read.
  void set_analog_input(int input, int millivolts) noexcept;
  [[nodiscard]] int analog_input(int input) const noexcept;
  /// The B017 average of AE`input` now, mV (what V007..V010 and the override see).
  [[nodiscard]] double analog_average(int input) const noexcept;
  /// Whether the flying cutoff's cut is inhibited now (A133).
  [[nodiscard]] bool cut_inhibited() const noexcept { return cut_.inhibited; }

  /// Battery-buffered state: program, logic, variables, counters, retentive markers, run state
  /// and the restart snapshot. from_json() restores it as after a power loss (restart possible
  /// when a program was running in Automatic).
  [[nodiscard]] nlohmann::json to_json() const;
  std::expected<void, std::string> from_json(const nlohmann::json& j);

 private:
  enum class Flow : std::uint8_t { next, jump, wait, halt };
  struct Task {
    bool used = false;
    int start = 0;
    int pc = 0;
    std::vector<int> stack;
    bool active = false;
    int phase = 0;                 ///< progress of a waiting instruction (0 = not started)
    TimePoint until{};             ///< WAI deadline
    int aux = 0;                   ///< per-instruction scratch (MAT cycles left, ...)
    int jump_to = 0;               ///< target when exec returns Flow::jump
    bool restart_program = false;  ///< task 1 runs the B016 restart program
    bool manual_vector = false;    ///< task 1 runs the B014 manual vector program
  };
  struct Vcc {
    bool active = false;
    bool absolute = false;
    double at = 0.0;  ///< CLM coordinates: the position at which to switch / to have reached v
    double velocity = 0.0;
  };
  /// NC cycles over which the actual velocity is measured (8: 16 ms at 2 ms; one encoder
  /// increment of standstill jitter reads as a few thousandths of Vmax, not as motion).
  static constexpr std::size_t velocity_window = 8;
  struct AxisRun {
    AxisPort* port = nullptr;
    AxisFeedback fb{};
    /// The actual positions of the last velocity_window NC cycles (a ring): the CLM's actual
    /// velocity is its encoder travel over that window (fb.velocity is that, not the drive's
    /// instantaneous reading; docs/clm14.md).
    std::array<double, velocity_window> positions{};
    std::size_t positions_seen = 0;
    double base = 0.0;  ///< CLM position = raw + base (homing) + sac
    double sac = 0.0;   ///< SAC offset
    bool homed = false;
    bool homing = false;          ///< a homing run is active (HOM, the Ax23 input)
    bool homing_restart = false;  ///< Automatic: stopped by Immediate Stop / JST, HOM again on Start
    Homing homer;
    std::int64_t marker_last_inc = 0;  ///< actual increments of the previous cycle (marker passage)
    bool marker_input_last = false;    ///< MarkerSource::input in the previous cycle
    bool home_switch_last = false;     ///< the Ax23 home switch in the previous cycle (option 5)
    std::optional<bool> homed_out;     ///< the Ax24 output as last written (written on change)
    // axis_inputs.cpp: B017 override inputs, Ax15, Ax30, Ax32
    double input_override = 1.0;         ///< B017 factor applied now (1 when off or VEO rules)
    bool override_stopped = false;       ///< a feed stopped by a B017 override of 0
    bool feed_angle_last = false;        ///< Ax15 feed-angle input in the previous cycle
    bool interrupted = false;            ///< Ax15 interrupt input lost: the feed / CON stopped, resumes on its return
    bool roll_open = false;              ///< Ax30: the feed roll is open (command 0: the drive is disabled)
    double command_velocity_last = 0.0;  ///< Ax32: the set-point velocity of the previous cycle
    double target = 0.0;                 ///< CLM coordinates
    bool has_target = false;             ///< a feed is commanded (target valid)
    bool feeding = false;                ///< the target is not reached yet (remaining distance > window)
    bool held = false;                   ///< stopped by JST/Immediate Stop/!STOP: resume to target on Start
    bool pending = false;                ///< commanded while the drive was still enabling: sent once it is
    double move_start = 0.0;             ///< CLM position where the last move started (VCC mode 0)
    double velocity = 0.0;               ///< IU/s of the current feed
    int acc_permille = 0;                ///< ACC (0 = Ax09)
    int dec_permille = 0;
    Micro fak = micro_one;
    int rtm = 0;  ///< 0 from Ax05, 1 shortest, 2 programmed direction
    bool con = false;
    double con_velocity = 0.0;
    bool srm = false;  ///< SRM searching
    BitAddress srm_input{};
    bool srm_input_last = false;
    double srm_offset = 0.0;
    double srm_start = 0.0;
    double latched = 0.0;
    bool srm_rep_hit = false;
    bool rep = false;
    int rep_line = 0;
    double rep_distance = 0.0;
    bool software_enabled = true;
    bool drive_enable = false;
    TimePoint enable_since{};
    int override_permille = 1000;  ///< VEO source 4
    bool override_master = false;  ///< VEO source 5 / 6: override = ME velocity / Vmax × FOL factor
    int override_encoder = 1;      ///< VEO source 5: master encoder 1; 6: master encoder 2 [decided]
    double master_override = 1.0;
    int feed_permille = 999;  ///< ‰ of the running feed (re-planned when the VEO 5 override moves)
    bool aeo = false;         ///< AEO: acceleration from the ME1 velocity
    int aeo_scale = 1000;
    int aeo_min = 0;
    bool override_limit = false;
    bool presignal = false;
    bool rmi_suspended = false;  ///< task-1 feed suspended by RMI
    double rmi_saved_target = 0.0;
    double rmi_base = 0.0;
    bool rmi_offset_pending = false;
    bool jog = false;
    double presignal_since_s = 0.0;
    TimePoint presignal_on{};
  };
  /// Master encoder 1 as read this cycle.
  struct MasterIn {
    MasterEncoderPort* port = nullptr;
    motion::EncoderInput input{32};
    std::int64_t count = 0;  ///< unwrapped quadrature counts, C001 direction applied
    std::array<std::int64_t, velocity_window> history{};
    std::size_t seen = 0;
    double velocity = 0.0;       ///< counts/s over the velocity window
    std::int64_t offset = 0;     ///< count = encoder + offset (continues where the internal material left it)
    bool internal = false;       ///< test mode / No Material: the count integrates a speed
    double internal_rest = 0.0;  ///< fraction of a count not yet added
    std::int64_t last = 0;       ///< count of the previous cycle (length counters)
    std::int64_t encoder = 0;    ///< the encoder's count of the previous cycle

    /// This cycle's count into the velocity window (8 NC cycles, as for the axes); with
    /// `measure`, `velocity` becomes the counts/s over the window (0 in the first cycle).
    void record(double cycle_ms, bool measure) noexcept {
      const std::size_t n = std::min(seen, velocity_window);
      if (measure) {
        const std::int64_t oldest = n == 0 ? count : history[(seen - n) % velocity_window];
        velocity = n == 0 ? 0.0 : static_cast<double>(count - oldest) / (static_cast<double>(n) * cycle_ms / 1000.0);
      }
      history[seen % velocity_window] = count;
      ++seen;
    }
  };
  /// Measuring-wheel mode of axis 1 (master encoder 1) / axis 2 (master encoder 2), manual §7.2.
  struct Wheel {
    bool active = false;      ///< the wheel closes the loop (Automatic, Ax31); else the motor
    bool have_last = false;   ///< last_wheel / last_motor are valid
    double last_wheel = 0.0;  ///< wheel travel (IU) of the previous cycle
    double last_motor = 0.0;  ///< motor position (axis IU) of the previous cycle
    /// Axis position - motor position: the wheel-motor difference gathered while the wheel was
    /// active (the axis position is the sum of the wheel's moves then, of the motor's otherwise).
    double offset = 0.0;
    bool revolution = false;  ///< Ax16: rev_wheel / rev_motor hold the current revolution's start
    double rev_wheel = 0.0;
    double rev_motor = 0.0;
    bool tolerance2 = false;   ///< Ax16 window 2 exceeded in this or the previous revolution
    bool exceeded2 = false;    ///< ... in this revolution
    bool correcting = false;   ///< the running move's motor target takes the difference
    double move_offset = 0.0;  ///< offset when the move was commanded
    double move_length = 0.0;  ///< |its distance| (the correction's bound)
    double commanded = 0.0;    ///< the motor target last sent (axis coordinates)
    double applied = 0.0;      ///< the offset the motor target carries (follows `offset`)
  };
  /// FOL / flying-cutoff coupling of one axis (hil::motion::Coupling, gear law).
  struct Follow {
    motion::Coupling coupling{"clm"};
    bool active = false;  ///< the coupling drives the axis this cycle
    bool fol = false;     ///< FOL on (else the flying cutoff owns it)
    int mode = 1;         ///< FOL mode 1 (steps) / 2 (ramps)
    Micro factor = micro_one;
    bool ending = false;  ///< mode 2 off: the ratio ramps to 0, then the axis stands
    bool paused = false;  ///< mode 2: ramped out by Immediate Stop, re-synchronised by Start
  };
  /// The flying cutoff of axis 1 (mode 5), in master-encoder counts.
  struct Cutoff {
    enum class Phase : std::uint8_t { idle, armed, synchronous, returning, inhibited };
    Phase phase = Phase::idle;
    bool have_last = false;
    std::int64_t last_cut = 0;             ///< material point (counts) cut last
    std::int64_t cut_at = 0;               ///< the armed instruction's cut point
    std::int64_t ramp = 0;                 ///< master counts of the engage ramp
    std::int64_t registration_offset = 0;  ///< LMK/LMR: counts from the raster to the cut
    bool registration = false;
    bool raster_used = false;            ///< once per instruction
    std::optional<std::int64_t> raster;  ///< first raster since de-sync (counts)
    bool raster_last = false;
    std::uint64_t cuts = 0;
    std::int64_t part = 0;               ///< the armed part's length (counts): the next one's estimate (A139)
    bool inhibited = false;              ///< A133: no sync until Immediate cut
    bool immediate = false;              ///< A134 in Automatic: the next arming syncs at once
    bool at_once = false;                ///< the armed engage started at once (immediate cut): no re-arm
    bool crop = false;                   ///< A142: the next part is the crop length
    int pending_error = 0;               ///< 3B / 3C: raised at the EOS of the rapid-stop / max-stroke program
    bool braking = false;                ///< A139: the carriage brakes at A108 before its optimised return
    double return_acceleration = 0.0;    ///< A139: the optimised return's acceleration (IU/s², 0 = A108)
    double return_material_speed = 0.0;  ///< material speed (IU/s) the optimised return was planned for
  };
  struct Mlo {
    bool on = false;
    BitAddress bit{};
    double length = 0.0;
    double ref = 0.0;  ///< processed length at which the current interval started
  };
  struct Srp {
    int mode = 0;  ///< 0 off, 1 correct the next feed, 2 correct now, 3 detect only
    int base = 600;
    int task = 0;  ///< the task whose PSI measures
    ByteAddress flag{};
    bool armed = false;      ///< the next PSI of axis 1 measures
    bool measuring = false;  ///< a PSI measures now
    bool missed = false;     ///< the window passed without a mark: the PSI jumps to base+5
    double start = 0.0;
    bool raster_last = false;
    double correction = 0.0;  ///< mode 1: added to the next feed
  };

  struct Restart {
    bool valid = false;
    std::array<int, 5> pc{};
    std::array<int, 5> phase{};  ///< a PSI/PSA waiting for its window resumes waiting, not moving again
    std::array<std::vector<int>, 5> stack{};
    std::array<bool, 5> active{};
    std::array<double, 4> target{};
    std::array<bool, 4> has_target{};
    std::array<std::uint8_t, 7> outputs{};
  };

  // controller.cpp
  void apply_parameters(TimePoint now);
  void compile_logic();
  void update_mode(TimePoint now);
  void enter_mode(Mode m, TimePoint now);
  void update_safety(TimePoint now);
  void update_axes_in(TimePoint now);
  void update_system_variables();
  void update_outputs();
  void raise(int code, std::string message, int item_kind = -1, int item = 0);
  void stop_program(bool keep_position);
  void start_program(TimePoint now);
  void resume_program();
  void start_manual_vector(int line);  ///< task 1 runs the program at `line` (B014 / A134 manual cut) up to its RTS
  void save_restart();
  void restore_restart(bool outputs);
  void reset_volatile_axis_state();
  void run_tasks(TimePoint now);
  void step_task(int t, TimePoint now);
  void clear_nc_markers();
  void write_bit(const BitAddress& a, bool v);
  void write_byte(const ByteAddress& a, std::uint8_t v);
  // commands.cpp
  Flow exec(int t, Task& task, const Instruction& in, TimePoint now);
  Flow exec_logic_ops(int t, Task& task, const Instruction& in);
  Flow exec_counter(Task& task, const Instruction& in, int line);
  [[nodiscard]] std::optional<Micro> value(const Num& n, int t);
  /// An integer operand in lo..hi; a variable's fraction is truncated (§5.6: V601 = +999.9999 -> 999).
  /// Out of range: error 32 for a variable, 0A for a constant. nullopt after raising.
  [[nodiscard]] std::optional<int> integer(const Num& n, int t, int lo, int hi);
  /// A 6.3 length field (±999999.999, truncated to 3 decimals); error 32 when it does not fit.
  [[nodiscard]] std::optional<Micro> length(const Num& n, int t);
  void fail(int t, int code, std::string why);
  [[nodiscard]] bool forbidden_in_cutoff(const Instruction& in) const;
  bool store_variable(int var, Micro v, int t);
  // motion.cpp
  Flow exec_motion(int t, Task& task, const Instruction& in, TimePoint now);
  /// The move limits of `axis` at `velocity` (IU/s): Ax08 × ACC/Ax09 ‰, AEO, the Ax10 jerk;
  /// `overridden` = the B017 input override scales the velocity (not for homing, §7.3).
  [[nodiscard]] MoveLimits limits_for(int axis, double velocity, bool overridden = true) const;
  [[nodiscard]] double feed_velocity(int axis, int permille) const;
  bool command_move(int axis, double target_clm, double velocity, int t);
  void resume_axis(int axis);
  void hold_axis(int axis);
  [[nodiscard]] double clm_position(int axis) const;
  [[nodiscard]] double raw_of(int axis, double clm) const;
  [[nodiscard]] bool reached(int axis) const;
  void step_axis_functions(TimePoint now);
  void jog(TimePoint now);
  // axis_inputs.cpp: B017 override inputs, Ax15 feed angle / interrupt, Ax30 open feed roll, Ax32
  /// The B017 override factor of `axis` from the inputs now (1 = off; VEO has priority).
  [[nodiscard]] double input_override(int axis) const;
  /// Feed lines of `axis` wait: Ax15 feed angle or interrupt missing, Ax30 roll open.
  [[nodiscard]] bool feed_blocked(int axis) const;
  void step_axis_inputs();
  // homing_run.cpp: the CLM's own homing (homing.hpp), the Ax23 input, option 5, the Ax24 output
  /// Start homing axis `axis` (HOM in task `t`, or t = 0 for the Ax23 homing input). False when
  /// it cannot start (the error is raised).
  bool start_homing(int axis, int t);
  void step_homing(int axis);
  /// End a homing run; `restart` = HOM again at the next Start (Automatic, §7.9).
  void abort_homing(int axis, bool restart);
  [[nodiscard]] HomingInput homing_input(int axis);
  void apply_homing(int axis, const HomingCommand& c);
  void set_home(int axis, std::int64_t home_inc);
  // coupled.cpp: master encoder, FOL, FUN, MLO/MLT, AEO, VEO 5, SRP
  void update_master_in();
  Flow exec_coupled(int t, Task& task, const Instruction& in);
  void step_couplings(TimePoint now);
  void end_coupling(int axis, bool stop_axis);
  [[nodiscard]] std::int64_t follow_ramp(int axis, double ratio_change) const;
  void pause_follow(int axis, bool pause);
  void reset_coupled_state();
  [[nodiscard]] bool master_available() const noexcept;
  // measuring_wheel.cpp: Ax00 modes 3/4, Ax16, Ax31, V047/V048
  void step_wheels();
  void step_wheel(int axis);
  [[nodiscard]] double wheel_offset(int axis) const noexcept;
  /// A move of `axis` was commanded (its target is set): the wheel correction starts.
  void on_wheel_move(int axis);
  /// Homing / Parameter mode: the axis and motor positions are the same again.
  void reset_wheel(int axis);
  /// SET V047 / V048 while not homed: the motor position becomes `v`, the axis position stays.
  bool set_motor_position(int axis, double v);
  // axis_inputs.cpp: the analog inputs' B017 average, V007..V010
  void update_analog_in();
  // master_encoder2.cpp
  void update_master2_in();
  [[nodiscard]] bool master2_available() const noexcept;
  /// The override of VEO source 5 / 6 of `axis` now: |v_ME| / Ax06 × FOL factor.
  [[nodiscard]] double encoder_override(int axis) const;
  [[nodiscard]] double me_iu_per_count() const noexcept;
  [[nodiscard]] std::optional<std::int64_t> master_counts(int axis) const;
  [[nodiscard]] std::optional<motion::GearRatio> follow_ratio(int axis, Micro factor) const;
  [[nodiscard]] double inc_per_iu(int axis) const;
  [[nodiscard]] motion::SlaveLimits slave_limits(int axis) const;
  [[nodiscard]] double processed_length() const;
  void update_measurements();
  void step_srp();
  bool superimpose(int axis, double distance, double velocity, int t);
  // flying_cutoff.cpp: LML/LMK/LMR/EOS, the carriage cycle
  Flow exec_cutoff(int t, Task& task, const Instruction& in);
  void step_cutoff();
  // cutoff_functions.cpp: A133-A142, C008, test mode, the length counters
  void step_cutoff_inputs();
  void update_internal_material(std::int64_t encoder_count, bool have_encoder);
  void cutoff_program(int line, int code);
  void cutoff_stop(int code, std::string message);
  void command_return(bool optimise);
  void step_optimised_return();
  [[nodiscard]] double optimised_return_acceleration() const;
  [[nodiscard]] bool carriage_home() const;
  [[nodiscard]] double carriage_counts() const;
  void end_cutoff();
  [[nodiscard]] std::int64_t cutoff_ramp() const;
  bool arm_cutoff_engage();
  [[nodiscard]] bool flying_cutoff() const noexcept;
  /// Task 1's start line on Manual -> Automatic (§7.12, A138): 0000 or the line before the last
  /// length instruction.
  [[nodiscard]] int cutoff_start_line();

  Options options_;
  ParameterLookup parameters_;
  std::function<std::expected<void, ProgramError>()> validator_;
  std::function<void(const Settings&)> on_settings_;
  Settings settings_;
  bool settings_ok_ = false;
  std::vector<Instruction> program_;
  std::vector<std::string> text_;
  std::vector<std::string> logic_text_;
  LogicProgram logic_;
  bool logic_ok_ = false;
  TimePoint logic_next_{};
  std::array<Micro, 1000> vars_{};
  std::map<int, int> counters_;  ///< line -> count (retentive)
  Image image_;
  Image previous_inputs_;  ///< for edges
  std::array<Task, 5> tasks_{};
  std::array<AxisRun, 4> axes_{};
  Mode mode_ = Mode::manual;
  bool mode_valid_ = false;  ///< false until the first cycle after power-up
  RunState run_ = RunState::idle;
  bool stopped_by_command_ = false;  ///< !STOP: only !START resumes
  int error_ = 0;
  std::string error_message_;
  std::array<std::string, 4> error_item_{};
  std::string txt53_;
  std::array<std::string, 4> txt63_{};
  Restart restart_;
  bool restart_blocked_ = false;  ///< after Lag/Runaway on an incremental encoder
  std::uint64_t cycle_count_ = 0;
  std::uint64_t auto_cycles_ = 0;
  double hours_ms_ = 0.0;  ///< operating time for V019
  TimePoint now_{};
  bool powered_ = false;
  int mat_owner_ = -1;  ///< task using the calculation unit
  MasterIn me1_{};
  Micro fak5_ = micro_one;  ///< FAK 5: factor on the C002 feed constant
  std::array<Follow, 4> follow_{};
  Cutoff cut_{};
  std::array<double, 7> fun_ref_{};  ///< FUN channel references (measure at the last restart)
  Mlo mlo_{};
  Srp srp_{};
  int test_step_ = 0;                          ///< test mode speed step (CTA keys)
  std::array<int, 4> analog_mv_{};             ///< AE1..AE4, mV
  std::array<AnalogAverage, 4> analog_avg_{};  ///< B017 averaging of AE1..AE4
  std::optional<std::int64_t> manual_cut_;     ///< material point (counts) under the tool at the last manual cut
  double material_length_ = 0.0;               ///< status 54, IU
  double product_length_ = 0.0;
  int last_srm_axis_ = 0;
  bool inhibit_ = false;          ///< Inhibit Operation (Q0.01.5): a move was blocked this cycle
  MasterIn me2_{};                ///< master encoder 2 (C004-C006)
  std::array<Wheel, 2> wheel_{};  ///< measuring wheel of axes 1 and 2
  int cutoff_length_line_ = -1;   ///< flying cutoff: the line of task 1's last length instruction (A138)
  bool start_0000_ = false;       ///< A138 input edge / !CL0 in Manual: the next start is at 0000
};

[[nodiscard]] const char* to_string(Mode m) noexcept;

}  // namespace hil::controllers::clm14
