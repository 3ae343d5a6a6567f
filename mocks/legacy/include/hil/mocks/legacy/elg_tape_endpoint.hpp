// SPDX-License-Identifier: MIT
#pragma once
// Emulated SINUMERIK ELG universal interface as a tape reader/punch partner (manual ch. 9-10):
// accepts %TEA1 (machine data) and %SEA (setting data) tapes in ISO code and punches them on
// request. A tape is taken over only when it was read completely and every datum is valid
// (otherwise the ELG alarm is raised and nothing changes). Output starts on "Data Start",
// given remotely by a DC2 byte (our convention, see docs/serial.md) or by the console.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "hil/mocks/legacy/endpoint.hpp"
#include "hil/serial/tape/elg_tape.hpp"

namespace hil::mocks::legacy {

/// Checks one datum against the device profile: empty = valid, else the reason.
using ElgDatumCheck =
    std::function<std::optional<std::string>(serial::tape::ElgSectionKind, int number, const std::string& value)>;

struct ElgEndpointOptions {
  serial::tape::TapeReaderOptions reader{.accept_eia = false};  ///< MD/SD only in ISO (§9.3)
  serial::tape::TapeWriterOptions writer{.block_end = serial::tape::TapeWriterOptions::BlockEnd::lf_cr_cr};
  Duration idle_timeout = std::chrono::seconds(60);  ///< alarm 22 when a started tape stalls
};

class ElgTapeEndpoint final : public Endpoint {
 public:
  ElgTapeEndpoint(ElgDatumCheck check, ElgEndpointOptions o = {});

  std::string on_bytes(std::span<const std::uint8_t> data, TimePoint now) override;
  std::string on_line_error(std::error_code ec, TimePoint now) override;
  std::string on_idle(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override { return deadline_; }
  bool take_dirty() override { return std::exchange(dirty_, false); }
  std::string save_state() const override;
  std::expected<void, std::string> load_state(const std::string& text);

  /// "Data Start" in DATA OUTPUT: the next section's tape (MD first, then SD), as bytes.
  [[nodiscard]] std::string data_start_output();
  /// Current alarm number (0 = none) and its reason.
  [[nodiscard]] int alarm() const noexcept { return alarm_; }
  [[nodiscard]] const std::string& alarm_text() const noexcept { return alarm_text_; }
  void clear_alarm() {
    alarm_ = 0;
    alarm_text_.clear();
  }
  [[nodiscard]] const std::map<int, std::string>& machine_data() const noexcept { return md_; }
  [[nodiscard]] const std::map<int, std::string>& setting_data() const noexcept { return sd_; }
  void set_datum(serial::tape::ElgSectionKind k, int number, std::string value);
  /// The ELG's MD or SD store itself (the PC data channel writes it); mark_dirty() after a change.
  [[nodiscard]] std::map<int, std::string>& store(serial::tape::ElgSectionKind k) noexcept {
    return k == serial::tape::ElgSectionKind::machine_data ? md_ : sd_;
  }
  void mark_dirty() noexcept { dirty_ = true; }
  /// A tape is being read in (Data Start bytes are data then).
  [[nodiscard]] bool reading() const noexcept { return reading_; }
  /// An alarm of the running ELG on its V.24 side (2214: transfer refused while coupled).
  void report(int alarm, std::string text) { raise(alarm, std::move(text)); }

 private:
  void finish_tape();
  void raise(int alarm, std::string text);

  ElgDatumCheck check_;
  ElgEndpointOptions o_;
  serial::tape::TapeReader reader_;
  std::vector<std::string> blocks_;
  bool reading_ = false;
  TimePoint deadline_ = TimePoint::max();
  bool next_output_sd_ = false;
  std::map<int, std::string> md_;
  std::map<int, std::string> sd_;
  int alarm_ = 0;
  std::string alarm_text_;
  bool dirty_ = false;
};

}  // namespace hil::mocks::legacy
