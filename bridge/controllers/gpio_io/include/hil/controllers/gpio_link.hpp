// SPDX-License-Identifier: MIT
#pragma once
// One GPIO chip wired to a controller's image (the scenario's `io_links: - gpio:` entry): opens
// the lines (libgpiod 1.6 on a real chip, gpio-sim in the kernel label; or in-process mock lines,
// `chip: mock`) and owns the GpioInputs source and the GpioOutputs sink over them.
// Thread: open() at configuration time (it blocks for a few ioctls); the source and sink on the
// cycle thread.

#include <cstdint>
#include <expected>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hil/controllers/gpio_io.hpp"
#include "hil/controllers/io_image.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/fault.hpp"
#include "hil/gpio/line_bank.hpp"
#include "hil/gpio/line_config.hpp"

namespace hil::gpio::mock {
class MockLines;
}

namespace hil::controllers {

struct GpioLinkLine {
  std::string signal;              ///< the image signal (messages, the line's consumer role)
  std::optional<unsigned> offset;  ///< chip offset, or
  std::string name;                ///< a line name looked up on the chip
  BitAddress bit;
  bool active_low = false;  ///< image bit = !line level
  gpio::Bias bias = gpio::Bias::as_is;
  /// Mock chips only: the input level over scenario time (from the first cycle); 0 before the first.
  std::vector<std::pair<Duration, bool>> mock;
};

struct GpioLinkConfig {
  std::string chip;  ///< "mock" or a chip libgpiod can look up (name, path, label, number)
  std::string consumer = "hilbridge";
  std::vector<GpioLinkLine> inputs;
  std::vector<GpioLinkLine> outputs;
};

class GpioLink {
 public:
  /// Opens and requests every line (inputs with their bias, outputs low). Errors say which chip
  /// and line and why (busy, no such line, permission).
  [[nodiscard]] static std::expected<std::unique_ptr<GpioLink>, std::string> open(GpioLinkConfig config,
                                                                                  const Clock& clock);
  ~GpioLink();
  GpioLink(const GpioLink&) = delete;
  GpioLink& operator=(const GpioLink&) = delete;

  /// The inputs as one IoSource (nullptr without inputs) and the outputs as one IoSink (nullptr
  /// without outputs); both live as long as the link.
  [[nodiscard]] IoSource* source() noexcept;
  [[nodiscard]] IoSink* sink() noexcept { return outputs_ ? outputs_.get() : nullptr; }
  [[nodiscard]] const GpioLinkConfig& config() const noexcept { return config_; }
  /// Read and write errors so far (a failed read sets its bit to 0).
  [[nodiscard]] std::size_t errors() const noexcept;
  /// Outages so far (runs of cycles with a failed read or write), and the newest one as a fault:
  /// the errno, the chip, the line and its signal. Not for the cycle thread (it allocates).
  [[nodiscard]] std::uint64_t fault_count() const noexcept;
  [[nodiscard]] Fault fault() const;
  /// The mock lines behind a `chip: mock` link (tests), else nullptr.
  [[nodiscard]] gpio::mock::MockLines* mock_lines() noexcept { return mock_; }

 private:
  class Source;
  explicit GpioLink(GpioLinkConfig config);
  GpioLinkConfig config_;
  std::unique_ptr<gpio::LineBank> lines_;
  gpio::mock::MockLines* mock_ = nullptr;
  std::unique_ptr<GpioInputs> inputs_;
  std::unique_ptr<GpioOutputs> outputs_;
  std::unique_ptr<Source> source_;
  std::vector<std::string> line_signals_;  ///< per LineBank index: the signal it carries
};

}  // namespace hil::controllers
