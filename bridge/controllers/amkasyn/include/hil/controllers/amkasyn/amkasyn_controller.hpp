// SPDX-License-Identifier: MIT
#pragma once
// The AMKASYN PS fast functions as a controller of the runtime (docs/amkasyn.md, "Scenarios"):
//   controller: {device: amkasyn-sf, parameters: sf0.txt, programs: [sf1.txt],
//                tables: "16=db16.txt", cycle: 1ms, aw1: S, az1: M}
// owns an SfRuntime, initialises every SF file's init DB (FB 207) at construction, commands its
// commanding DB (FB 208) at power-up (`start: auto`) or on the scenario's command bits, and runs
// one SF cycle per controller cycle (the controller cycle is drive parameter ID 2).
//
// Image (the PS's own, byte for byte): input byte n = E n, output byte n = A n, marker byte n =
// M n. Data area: byte n (n = SF number 0..15) holds the PLC's FB 208 command bits of SF n
// (bit 0 `sfN_start`, bit 1 `sfN_reset`, bit 2 `sfN_value_new`, bit 3 `sfN_read_value`: rising
// edges) and its status
// (bit 4 `sfN_active` = SF-ACTIVE, bit 5 `sfN_error` = MB 232 error bit of its last command);
// bytes 16..271 are the PLC program's flag writes: flag byte n is copied from data byte 16 + n
// before every SF cycle unless an SF writes it (outputs in M, MW/MD sinks) or it is MB 232/233.
// resolve_bit("M 100.0") gives the marker when SFs write that byte, else the PLC's flag bit.
//
// Drives: AW n (aw1..aw8) is a machine axis in increments (units "inc"). An SF sink SWQ1 (16-bit
// position, wrapping), SWQ2 in position mode (ID 32800 = 3C0404) or SWQ2 in speed mode (3C0043,
// 0.0001 rpm) becomes Axis::follow() set-points; the sources read the axis: position feedback
// (actual increments), message32 per ID 32786 (position feedback, 36 velocity command, 40
// velocity feedback in 0.0001 rpm, 32824 following error). AZ message k (az1..az4) counts the
// actual increments of an axis (the pulse-generator input X32), in the high word when an SF reads
// it as a 16-bit source (offsets 1/3/5/7), else as 32 bits.
//
// Errors: a failed FB 208 is a device error of the catalogue sf_status (the code of MB 233); a
// DFKT's output table status bits (Tab7 DW1) are self-clearing device errors of the catalogue
// dfkt_status (the bit's value: 1, 2, 4, ..., 32), raised when the SF sets the bit and cleared
// when it clears it; both on the axis of the AW the SF writes (else reads), else the whole PS. An
// axis fault stays motion:N (the PS has no axis error numbers).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/amkasyn/analog_schedule.hpp"
#include "hil/controllers/amkasyn/db_text.hpp"
#include "hil/controllers/amkasyn/sf_runtime.hpp"
#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/parameter_file.hpp"

namespace hil::controllers::amkasyn {

/// Drive operating mode of an AW (ID 32800): what its SWQ2 means.
enum class AwMode : std::uint8_t {
  swq1_position,  ///< 3C0004: 16-bit position command SWQ1 x the drive ratio ID 32893 / ID 32892
  swq2_position,  ///< 3C0404: 32-bit position command SWQ2 (fine interpolation)
  swq2_speed,     ///< 3C0043: 32-bit speed command SWQ2 in 0.0001 rpm
};

/// One AW drive on a machine axis.
struct AwChannel {
  std::size_t axis = 0;                 ///< index into the controller's axes
  AwMode mode = AwMode::swq1_position;  ///< which sink drives the axis
  int message32 = 0;                    ///< ID 32786: 0 position feedback, 36, 40, 32824
  std::int64_t ratio_mul = 1;           ///< ID 32893 (0 -> 1): SWQ1 differences x mul / div
  std::int64_t ratio_div = 1;           ///< ID 32892 (0 -> 1, else 2^16..2^31-1)
};

/// One AZ message counting an axis.
struct AzChannel {
  std::size_t axis = 0;
  bool high_word = false;  ///< the count sits in the high word (16-bit sources 1/3/5/7)
};

/// One SF as its file gives it.
struct SfFile {
  std::string file;
  SfDbText db;
  profiles::ParameterSet parameters;   ///< the validated set (profile engine)
  std::optional<DataBlock> value_new;  ///< the commanding DB sfN_value_new sends (else `db.command`)
  std::string value_new_file;
};

/// Everything the factory reads from the scenario's controller block.
struct AmkasynSetup {
  int id2_half_ms = 2;  ///< drive parameter ID 2 in 0.5 ms = the controller cycle
  std::vector<SfFile> sfs;
  DbStore tables;
  std::vector<std::pair<int, std::string>> fbs;  ///< APSF function blocks: FB number, AWL listing (parsed)
  std::array<std::optional<AwChannel>, 8> aw;
  std::array<std::optional<AzChannel>, 4> az;
  /// AW1..AW8 message16 (the analog input, key awN_message16): empty = no input, reads 0.
  std::array<AnalogSchedule, 8> aw_message16;
  std::int64_t resolution = 20000;  ///< increments per revolution (speed conversions)
  bool auto_start = true;
};

class AmkasynController final : public Controller {
 public:
  AmkasynController(std::shared_ptr<const profiles::Profile> profile, AmkasynSetup setup,
                    std::vector<ControllerAxis> axes);

  [[nodiscard]] std::expected<BitAddress, std::string> resolve_bit(std::string_view text) const override;
  /// "AA1_mV".."AA4_mV" for the analog outputs SFs write (10000 = 10 V).
  [[nodiscard]] std::vector<std::string> trace_signals() const override;
  [[nodiscard]] double trace_value(std::size_t i) const noexcept override;

  [[nodiscard]] const SfRuntime& runtime() const noexcept { return runtime_; }
  [[nodiscard]] const ProcessImage& process_image() const noexcept { return image_; }
  [[nodiscard]] const DbStore& tables() const noexcept { return setup_.tables; }
  /// The data-area bit of SF n's command / status bit `bit` (0 start, 1 reset, 2 value new,
  /// 3 read value, 4 active, 5 error).
  [[nodiscard]] static BitAddress command_bit(int sf, int bit) noexcept {
    return {IoArea::data, static_cast<std::uint32_t>(sf), static_cast<std::uint8_t>(bit)};
  }
  /// First data byte of the PLC's flag writes.
  static constexpr std::uint32_t plc_flags_base = 16;
  /// The data-area bit of the zero-pulse (reference) input of AZ message k (0..3): `azK_zero`.
  [[nodiscard]] static BitAddress zero_pulse_bit(int k) noexcept {
    return {IoArea::data, plc_flags_base + 256, static_cast<std::uint8_t>(k)};
  }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t, const hil::Fault&,
                                                              const motion::AxisStatus&) const noexcept override {
    return std::nullopt;
  }

 private:
  struct AxisDrive {
    bool ready = false;             ///< enabled; the channel's base is taken
    std::int64_t target_inc = 0;    ///< the set-point the SFs give (unwrapped)
    std::int32_t last_channel = 0;  ///< SWQ value of the last cycle
    std::int64_t speed_rest = 0;    ///< remainder of the speed integration / the SWQ1 ratio
    bool following = false;         ///< follow() was called (stop() when the set-point rests)
    int resting = 0;                ///< cycles without a set-point change
  };
  void command(int sf, int code, TimePoint now) noexcept;
  void report_dfkt_status(TimePoint now) noexcept;
  [[nodiscard]] int axis_of(const SfFile& file) const noexcept;
  void read_image(Duration since_first_cycle) noexcept;
  void write_image() noexcept;
  void drive_axes(double dt_s) noexcept;

  AmkasynSetup setup_;
  SfRuntime runtime_;
  ProcessImage image_{};
  std::array<bool, 256> flag_owned_{};  ///< M bytes SFs (or MB 232/233) write
  std::array<AxisDrive, 8> drives_{};
  std::vector<int> aa_used_;                         ///< analog outputs that are SF sinks (0..3)
  std::array<std::uint16_t, max_sf> dfkt_status_{};  ///< Tab7 DW1 as last reported, per SF
  std::optional<TimePoint> first_cycle_;             ///< the time origin of the awN_message16 schedules
  bool started_ = false;
  const profiles::ErrorCatalogue* sf_status_ = nullptr;
  const profiles::ErrorCatalogue* dfkt_catalogue_ = nullptr;
};

/// Registers `amkasyn-sf` in `registry`.
void register_amkasyn(ControllerRegistry& registry);

}  // namespace hil::controllers::amkasyn
