// SPDX-License-Identifier: MIT
#include "hil/gpio/linux/gpiod_lines.hpp"

#include <cerrno>

#include <fmt/format.h>
#include <gpiod.h>

namespace hil::gpio::linux_gpiod {
namespace {

std::error_code last_errno() noexcept {
  return {errno ? errno : EIO, std::generic_category()};
}

int request_flags(const LineSpec& s) noexcept {
  int flags = 0;
  if (s.active_low) flags |= GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW;
  switch (s.bias) {
    case Bias::as_is:
      break;
    case Bias::disabled:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
      break;
    case Bias::pull_up:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
      break;
    case Bias::pull_down:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
      break;
  }
  return flags;
}

std::string describe(const LineSpec& s) {
  return s.offset ? fmt::format("line '{}' (offset {})", s.role, *s.offset)
                  : fmt::format("line '{}' (name '{}')", s.role, s.name);
}

}  // namespace

std::expected<std::unique_ptr<GpiodLines>, OpenError> GpiodLines::open(std::string_view chip,
                                                                       const std::vector<LineSpec>& specs,
                                                                       std::string_view consumer) {
  std::unique_ptr<GpiodLines> self(new GpiodLines());
  self->chip_name_ = std::string(chip);
  errno = 0;
  self->chip_ = ::gpiod_chip_open_lookup(self->chip_name_.c_str());
  if (!self->chip_) {
    auto ec = last_errno();
    return std::unexpected(OpenError{
        fmt::format("{}: cannot open GPIO chip: {} (check /dev/{} exists and is accessible; `gpiodetect` lists chips)",
                    chip, ec.message(), chip),
        ec});
  }
  const std::string consumer_s(consumer);
  const unsigned chip_lines = ::gpiod_chip_num_lines(self->chip_);
  for (const LineSpec& s : specs) {
    gpiod_line* line = nullptr;
    errno = 0;
    if (s.offset) {
      if (*s.offset >= chip_lines) {
        return std::unexpected(OpenError{fmt::format("{}: {}: offset out of range, the chip has {} lines (0..{})", chip,
                                                     describe(s), chip_lines, chip_lines - 1),
                                         std::make_error_code(std::errc::invalid_argument)});
      }
      line = ::gpiod_chip_get_line(self->chip_, *s.offset);
    } else {
      line = ::gpiod_chip_find_line(self->chip_, s.name.c_str());
    }
    if (!line) {
      auto ec = errno ? last_errno() : std::make_error_code(std::errc::no_such_device);
      return std::unexpected(OpenError{
          fmt::format("{}: {}: not found: {} (`gpioinfo {}` lists the lines)", chip, describe(s), ec.message(), chip),
          ec});
    }
    gpiod_line_request_config cfg{};
    cfg.consumer = consumer_s.c_str();
    cfg.request_type =
        s.direction == LineDirection::output ? GPIOD_LINE_REQUEST_DIRECTION_OUTPUT : GPIOD_LINE_REQUEST_DIRECTION_INPUT;
    cfg.flags = request_flags(s);
    errno = 0;
    if (::gpiod_line_request(line, &cfg, s.initial ? 1 : 0) != 0) {
      auto ec = last_errno();
      return std::unexpected(
          OpenError{fmt::format("{}: {}: request failed: {} (is another program using it? bias needs kernel 5.5+)",
                                chip, describe(s), ec.message()),
                    ec});
    }
    self->lines_.push_back(line);
    self->directions_.push_back(s.direction);
  }
  return self;
}

GpiodLines::~GpiodLines() {
  for (gpiod_line* l : lines_) ::gpiod_line_release(l);
  if (chip_) ::gpiod_chip_close(chip_);
}

std::error_code GpiodLines::set_value(std::size_t index, bool level) noexcept {
  if (index >= lines_.size() || directions_[index] != LineDirection::output) {
    return std::make_error_code(std::errc::invalid_argument);
  }
  if (::gpiod_line_set_value(lines_[index], level ? 1 : 0) != 0) return last_errno();
  return {};
}

std::expected<bool, std::error_code> GpiodLines::get_value(std::size_t index) noexcept {
  if (index >= lines_.size()) return std::unexpected(std::make_error_code(std::errc::invalid_argument));
  const int v = ::gpiod_line_get_value(lines_[index]);
  if (v < 0) return std::unexpected(last_errno());
  return v != 0;
}

unsigned GpiodLines::offset(std::size_t index) const noexcept {
  return index < lines_.size() ? ::gpiod_line_offset(lines_[index]) : 0U;
}

}  // namespace hil::gpio::linux_gpiod
