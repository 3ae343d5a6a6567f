// SPDX-License-Identifier: MIT
#pragma once
// A running WF 725/726 behind 3964R/RK512 (`hilbridge emulate wf725`, docs/wf725.md, "The
// module on a serial line"): the data-block policy of hil::mocks::legacy::S5BlockEndpoint over
// the module's axes (1..3: A, B, C), each a Wf725Controller on a motion axis (simulated, or a
// machine file's real-transport drive), sharing one program memory and the user data blocks.
// RK512 SEND writes, FETCH reads (our mapping, the manual gives no serial framing):
//   DB <db axis> of each axis (10, 11, 12 by default): that axis' DB axis, DW 0..47, live
//     (wf725_interface.hpp): the PLC writes its command words, the module's status words are
//     rewritten every cycle.
//   DB 1 and DX k (k = 1..3, the k-th axis): the MD image of an axis (DB 1: the first axis),
//     MD 1..50 as 100 words (32-bit two's complement, high word first; MD 3 and MD 22 in 0.01
//     steps), the binary input format of §3.3. A SEND is taken only in that axis' mode
//     machine-data input/output (else refused with 06: WF message 201).
//   any other DB 2..255: a user data block (DW 0..255) in the endpoint's store (persisted in the
//     state file): what data codes 44/45 read a program from and write it to.
// The program memory (the module's, shared by its axes) is saved in the state file under
// "module" (the canonical text of its programs) and restored at the next start.
// The module cycles on the time the endpoint host passes in (`cycle` advances the machine one
// run period: axes, then the controllers at their cycle). Thread: the endpoint host's thread only.

#include <functional>
#include <string>
#include <vector>

#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf726_module.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

namespace hil::controllers::s5 {

inline constexpr std::uint8_t wf725_md_image_db = 1;        ///< DB 1: MD 1..50 of the first axis
inline constexpr std::size_t wf725_max_axes = 3;            ///< A, B, C
inline constexpr std::uint16_t wf725_md_image_words = 100;  ///< 50 MD x 2 words

class Wf725ModulePolicy final : public mocks::legacy::DbPolicy {
 public:
  /// `axes`: the module's 1..3 axes in the order A, B, C (non-null, alive as long as the policy,
  /// DB axis numbers distinct and not 1, letters distinct); they form one Wf726Module: they share
  /// the first axis' program memory from now on and run combined programs.
  /// `period`: the run period; `cycle` runs one period.
  Wf725ModulePolicy(std::vector<Wf725Controller*> axes, Duration period, std::function<void(const CycleTime&)> cycle);

  [[nodiscard]] std::string name() const override { return "wf725"; }
  serial::s5::Rk512Error on_write(mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                  const std::vector<std::uint16_t>& w) override;
  serial::s5::Rk512Error on_read(const mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                 std::uint16_t length, std::vector<std::uint16_t>& out) override;
  /// DX k (1..number of axes): the MD image of the k-th axis; other DX are refused (db_missing).
  serial::s5::Rk512Error on_write_dx(mocks::legacy::DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                     const std::vector<std::uint16_t>& w) override;
  serial::s5::Rk512Error on_read_dx(const mocks::legacy::DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                    std::uint16_t length, std::vector<std::uint16_t>& out) override;
  void on_time(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override;
  /// The canonical text of every stored program (make_wf725_program_text), in storage order.
  [[nodiscard]] std::string save_module_state() const override;
  /// Stores the saved programs whose number the memory does not hold yet (the programs given at
  /// power-up, `--program`, win); a text that does not parse or fit is an error naming why.
  std::expected<void, std::string> load_module_state(const std::string& text) override;
  /// True once after the program memory changed.
  [[nodiscard]] bool take_dirty() override;

  /// Lends the endpoint's DB store to every axis as its user data blocks (call once, before serving).
  void share_store(mocks::legacy::DbStore& store);
  [[nodiscard]] const std::vector<Wf725Controller*>& axes() const noexcept { return axes_; }
  [[nodiscard]] const Wf726Module& module() const noexcept { return module_; }
  /// Why the last refused job was refused (empty: none yet).
  [[nodiscard]] const std::string& last_rejection() const noexcept { return rejection_; }

 private:
  [[nodiscard]] Wf725Controller* axis_of_db(std::uint8_t db) const noexcept;
  serial::s5::Rk512Error write_md_image(Wf725Controller& a, std::uint8_t dw, const std::vector<std::uint16_t>& w);
  serial::s5::Rk512Error read_md_image(const Wf725Controller& a, std::uint8_t dw, std::uint16_t length,
                                       std::vector<std::uint16_t>& out);

  std::vector<Wf725Controller*> axes_;
  Wf726Module module_;
  Duration period_;
  std::function<void(const CycleTime&)> cycle_;
  TimePoint t_{};
  bool started_ = false;
  std::string rejection_;
  std::uint64_t saved_revision_ = 0;
};

}  // namespace hil::controllers::s5
