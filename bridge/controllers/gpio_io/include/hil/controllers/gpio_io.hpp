// SPDX-License-Identifier: MIT
#pragma once
// GPIO lines on the I/O image: GpioInputs reads input lines into image bits once per controller
// cycle (an IoSource), GpioOutputs drives output lines from image bits (an IoSink, writing only
// when a bit changed, retrying a failed write next cycle). A line that cannot be read reads 0
// (a de-energised input: a stale level must not look valid; an NC limit switch then reads
// active, the fail-safe side). A cycle with a failed line starts an outage when the cycle
// before had none (`outages()`): the runtime reports each outage once as a fault of the link. The LineBank is libgpiod
// on a real chip (gpio-sim in the kernel label) or the mock lines in tests. Thread: the cycle thread;
// get_value/set_value are non-blocking.

#include <cstddef>
#include <cstdint>
#include <system_error>
#include <vector>

#include "hil/controllers/io_image.hpp"
#include "hil/gpio/line_bank.hpp"

namespace hil::controllers {

struct GpioBit {
  std::size_t line = 0;     ///< index in the LineBank
  BitAddress bit;           ///< image bit
  bool active_low = false;  ///< image bit = !line level
};

class GpioInputs final : public IoSource {
 public:
  GpioInputs(gpio::LineBank& lines, std::vector<GpioBit> map) : lines_(lines), map_(std::move(map)) {}
  void read(TimePoint now, IoImage& image) noexcept override;
  /// Failed reads so far (each sets its bit to 0); the last error code and the LineBank index of
  /// the line it came from; outages (runs of cycles with a failed read).
  [[nodiscard]] std::size_t errors() const noexcept { return errors_; }
  [[nodiscard]] std::error_code last_error() const noexcept { return last_error_; }
  [[nodiscard]] std::size_t last_failed_line() const noexcept { return last_failed_line_; }
  [[nodiscard]] std::uint64_t outages() const noexcept { return outages_; }

 private:
  gpio::LineBank& lines_;
  std::vector<GpioBit> map_;
  std::size_t errors_ = 0;
  std::error_code last_error_;
  std::size_t last_failed_line_ = 0;
  std::uint64_t outages_ = 0;
  bool failing_ = false;
};

class GpioOutputs final : public IoSink {
 public:
  GpioOutputs(gpio::LineBank& lines, std::vector<GpioBit> map)
      : lines_(lines), map_(std::move(map)), written_(map_.size(), -1) {}
  void write(TimePoint now, const IoImage& image) noexcept override;
  [[nodiscard]] std::size_t errors() const noexcept { return errors_; }
  [[nodiscard]] std::error_code last_error() const noexcept { return last_error_; }
  [[nodiscard]] std::size_t last_failed_line() const noexcept { return last_failed_line_; }
  [[nodiscard]] std::uint64_t outages() const noexcept { return outages_; }

 private:
  gpio::LineBank& lines_;
  std::vector<GpioBit> map_;
  std::vector<int> written_;  ///< last level written per entry, -1 = never
  std::size_t errors_ = 0;
  std::error_code last_error_;
  std::size_t last_failed_line_ = 0;
  std::uint64_t outages_ = 0;
  bool failing_ = false;
};

}  // namespace hil::controllers
