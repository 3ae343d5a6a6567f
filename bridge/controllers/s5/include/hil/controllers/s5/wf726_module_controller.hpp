// SPDX-License-Identifier: MIT
#pragma once
// A WF 726 with several axes as one scenario controller (docs/wf725.md, "Several axes in a
// scenario"): `controller: {device: wf725-726, parameters: axis-a.txt, axis_b: axis-b.txt,
// axis_c: axis-c.txt, programs: [...]}` builds one Wf725Controller per axis (A from `parameters`,
// B and C from their MD lists), joined in one Wf726Module (one program memory, combined
// programs), and serves them to the runtime as one controller with one machine axis per module
// axis (named A, B, C). Each axis keeps its own image inside; this controller's image is theirs
// laid side by side:
//   inputs  4 bytes per axis (axis k at 4k: byte 1 its limit switches, 2 its encoder faults,
//           3 bit 6 its DAC readback); X7 E1..E6 (byte 0) and the supply checks (byte 3 bits
//           0..5) are the module's: the first axis' bytes, seen by every axis;
//   outputs byte 0 X7 A1..A6 (the module's connector: the OR of what each axis' MD 10 puts
//           there), byte 1 + k the status outputs of axis k (in_position_<axis>, ...);
//   markers byte 0 `device_error` (any axis);
//   data    the DB axis of axis k at 96k (its `db`: 10, 11, 12 unless `db_b` / `db_c`).
// Signal names are the axes' own (suffixed _A, _B, _C; the module's once). Device errors of an
// axis are shown on its machine axis (self-clearing mirrors: they go when the axis clears them;
// acknowledge through the DB axis, 800C or RESET). The user data blocks are shared by the axes.
// Thread: the cycle thread.

#include <memory>
#include <vector>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module.hpp"

namespace hil::controllers::s5 {

class Wf726ModuleController final : public Controller {
 public:
  /// `axes`: 2..3 axes of one module (distinct letters and DB numbers), the first one's profile
  /// and cycle are the module's.
  Wf726ModuleController(std::shared_ptr<const profiles::Profile> profile, profiles::ParameterSet parameters,
                        std::vector<std::unique_ptr<Wf725Controller>> axes);

  [[nodiscard]] std::expected<BitAddress, std::string> resolve_bit(std::string_view text) const override;
  [[nodiscard]] std::expected<std::uint16_t, std::string> read_data_word(int db, int dw) const override;
  std::expected<void, std::string> write_data_word(int db, int dw, std::uint16_t value) override;
  [[nodiscard]] std::span<const S5DataBlock> data_blocks() const noexcept override { return blocks_; }

  /// Axis k of the module (0 = the first, A).
  [[nodiscard]] Wf725Controller& module_axis(std::size_t k) noexcept { return *axes_[k]; }
  [[nodiscard]] const Wf726Module& module() const noexcept { return module_; }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] std::expected<void, std::string> check_axes() override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t, const hil::Fault&,
                                                              const motion::AxisStatus&) const noexcept override {
    return std::nullopt;  // each axis maps its own faults
  }

 private:
  /// Feeds axis k's image from this one at its read_inputs: inputs and the DB axis.
  struct Feed final : IoSource {
    Wf726ModuleController* owner = nullptr;
    std::size_t k = 0;
    void read(TimePoint now, IoImage& image) noexcept override;
  };
  [[nodiscard]] BitAddress outer(std::size_t k, BitAddress a) const noexcept;
  void mirror_errors(std::size_t k, TimePoint now) noexcept;

  std::vector<std::unique_ptr<Wf725Controller>> axes_;
  std::vector<std::unique_ptr<Feed>> feeds_;
  std::vector<S5DataBlock> blocks_;
  Wf725UserBlocks user_blocks_;
  Wf726Module module_;
};

/// The module controller from a `controller:` block with `axis_b` / `axis_c` (docs/wf725.md);
/// `create_axis` builds one axis from a single-axis spec.
[[nodiscard]] std::expected<std::unique_ptr<Controller>, ConfigError> make_wf726_module_controller(
    const ControllerSpec& spec,
    const std::function<std::expected<std::unique_ptr<Wf725Controller>, ConfigError>(const ControllerSpec&)>&
        create_axis);

}  // namespace hil::controllers::s5
