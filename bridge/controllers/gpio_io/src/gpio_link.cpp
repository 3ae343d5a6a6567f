// SPDX-License-Identifier: MIT
#include "hil/controllers/gpio_link.hpp"

#include <fmt/format.h>

#include "hil/gpio/linux/gpiod_lines.hpp"
#include "hil/mocks/gpio/mock_lines.hpp"

namespace hil::controllers {

// The inputs' IoSource: notes the first cycle's time (scenario time 0 of the mock scripts), then
// reads the lines through GpioInputs.
class GpioLink::Source final : public IoSource {
 public:
  explicit Source(GpioInputs& inputs) : inputs_(inputs) {}
  void read(TimePoint now, IoImage& image) noexcept override {
    if (!started_) {
      start_ns_ = now.time_since_epoch().count();
      started_ = true;
    }
    inputs_.read(now, image);
  }
  /// Scenario time of a clock reading; negative before the first cycle.
  [[nodiscard]] Duration scenario_time(std::int64_t t_ns) const noexcept {
    return started_ ? Duration{t_ns - start_ns_} : Duration{-1};
  }

 private:
  GpioInputs& inputs_;
  bool started_ = false;
  std::int64_t start_ns_ = 0;
};

GpioLink::GpioLink(GpioLinkConfig config) : config_(std::move(config)) {}
GpioLink::~GpioLink() = default;

IoSource* GpioLink::source() noexcept {
  return source_.get();
}

std::size_t GpioLink::errors() const noexcept {
  return (inputs_ ? inputs_->errors() : 0) + (outputs_ ? outputs_->errors() : 0);
}

std::uint64_t GpioLink::fault_count() const noexcept {
  return (inputs_ ? inputs_->outages() : 0) + (outputs_ ? outputs_->outages() : 0);
}

Fault GpioLink::fault() const {
  // The newer of the two sides' errors; with both failing the input side (it feeds the logic).
  const bool in = inputs_ && inputs_->last_error();
  const std::error_code ec = in ? inputs_->last_error() : (outputs_ ? outputs_->last_error() : std::error_code{});
  if (!ec) return {};
  const std::size_t line = in ? inputs_->last_failed_line() : outputs_->last_failed_line();
  const std::string signal = line < line_signals_.size() ? line_signals_[line] : "?";
  return Fault{ec, fmt::format("GPIO {}: {} line of '{}' failed: {}{}", config_.chip,
                               in ? "reading the input" : "writing the output", signal, ec.message(),
                               in ? " (the input reads 0 until the line reads again; check the chip and its wiring)"
                                  : " (retried every cycle; check the chip)")};
}

std::expected<std::unique_ptr<GpioLink>, std::string> GpioLink::open(GpioLinkConfig config, const Clock& clock) {
  std::unique_ptr<GpioLink> link(new GpioLink(std::move(config)));
  const GpioLinkConfig& c = link->config_;
  std::vector<gpio::LineSpec> specs;
  std::vector<GpioBit> in_map, out_map;
  const auto add = [&](const GpioLinkLine& l, gpio::LineDirection dir, std::vector<GpioBit>& map) {
    gpio::LineSpec s;
    s.role = l.signal;
    s.offset = l.offset;
    s.name = l.name;
    s.direction = dir;
    s.bias = l.bias;
    map.push_back({specs.size(), l.bit, l.active_low});
    link->line_signals_.push_back(l.signal);
    specs.push_back(std::move(s));
  };
  for (const auto& l : c.inputs) add(l, gpio::LineDirection::input, in_map);
  for (const auto& l : c.outputs) add(l, gpio::LineDirection::output, out_map);
  for (std::size_t i = 0; i < specs.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const bool same = specs[i].offset ? specs[i].offset == specs[j].offset : specs[i].name == specs[j].name;
      if (same) {
        return std::unexpected(fmt::format("{}: line {} is wired twice ('{}' and '{}')", c.chip,
                                           specs[i].offset ? std::to_string(*specs[i].offset) : specs[i].name,
                                           specs[j].role, specs[i].role));
      }
    }
  }

  if (c.chip == "mock") {
    auto mock = std::make_unique<gpio::mock::MockLines>(specs, clock);
    link->mock_ = mock.get();
    link->lines_ = std::move(mock);
  } else {
    auto real = gpio::linux_gpiod::GpiodLines::open(c.chip, specs, c.consumer);
    if (!real) return std::unexpected(real.error().message);
    link->lines_ = std::move(*real);
  }
  if (!in_map.empty()) {
    link->inputs_ = std::make_unique<GpioInputs>(*link->lines_, std::move(in_map));
    link->source_ = std::make_unique<Source>(*link->inputs_);
  }
  if (!out_map.empty()) link->outputs_ = std::make_unique<GpioOutputs>(*link->lines_, std::move(out_map));
  if (link->mock_ != nullptr) {
    for (std::size_t i = 0; i < c.inputs.size(); ++i) {
      if (c.inputs[i].mock.empty()) continue;
      link->mock_->set_input_source(i, [script = c.inputs[i].mock, src = link->source_.get()](std::int64_t t_ns) {
        const Duration t = src->scenario_time(t_ns);
        bool level = false;
        for (const auto& [at, v] : script) {
          if (at > t) break;
          level = v;
        }
        return level;
      });
    }
  }
  return link;
}

}  // namespace hil::controllers
