// SPDX-License-Identifier: MIT
#include "hil/controllers/io_image.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace hil::controllers {

std::string_view to_string(IoArea area) noexcept {
  switch (area) {
    case IoArea::input:
      return "input";
    case IoArea::output:
      return "output";
    case IoArea::marker:
      return "marker";
    case IoArea::data:
      return "data";
  }
  return "?";
}

IoImage::IoImage(IoLayout layout) : layout_(layout) {
  std::size_t total = 0;
  for (std::size_t i = 0; i < io_area_count; ++i) {
    offsets_[i] = total;
    total += layout_.bytes[i];
  }
  bytes_.assign(total, 0);
  previous_.assign(total, 0);
}

std::expected<void, std::string> IoImage::add_name(IoSignal signal) {
  if (signal.name.empty()) return std::unexpected(std::string("an I/O name must not be empty"));
  for (const auto& s : signals_) {
    if (s.name == signal.name) {
      return std::unexpected(
          fmt::format("I/O name '{}' is given twice (first for {} {})", signal.name, to_string(s.area), s.byte));
    }
  }
  signals_.push_back(std::move(signal));
  return {};
}

std::expected<void, std::string> IoImage::name_bit(std::string name, BitAddress address) {
  if (!contains(address)) {
    return std::unexpected(fmt::format("I/O name '{}': {} is outside the image ({} has {} bytes)", name,
                                       format_address(address), to_string(address.area), layout_.size(address.area)));
  }
  return add_name(IoSignal{std::move(name), address.area, address.byte, address.bit});
}

std::expected<void, std::string> IoImage::name_byte(std::string name, ByteAddress address) {
  if (!contains(address)) {
    return std::unexpected(fmt::format("I/O name '{}': {} is outside the image ({} has {} bytes)", name,
                                       format_address(address), to_string(address.area), layout_.size(address.area)));
  }
  return add_name(IoSignal{std::move(name), address.area, address.byte, std::nullopt});
}

std::optional<BitAddress> IoImage::find_bit(std::string_view name) const noexcept {
  const auto it = std::ranges::find_if(signals_, [&](const IoSignal& s) { return s.bit && s.name == name; });
  if (it == signals_.end()) return std::nullopt;
  return BitAddress{it->area, it->byte, *it->bit};
}

std::optional<ByteAddress> IoImage::find_byte(std::string_view name) const noexcept {
  const auto it = std::ranges::find_if(signals_, [&](const IoSignal& s) { return !s.bit && s.name == name; });
  if (it == signals_.end()) return std::nullopt;
  return ByteAddress{it->area, it->byte};
}

void IoImage::attach(IoSource& source) {
  sources_.push_back(&source);
}
void IoImage::attach(IoSink& sink) {
  sinks_.push_back(&sink);
}

void IoImage::read_inputs(TimePoint now) noexcept {
  std::ranges::copy(bytes_, previous_.begin());
  for (auto* s : sources_) s->read(now, *this);
}

void IoImage::write_outputs(TimePoint now) const noexcept {
  for (auto* s : sinks_) s->write(now, *this);
}

std::string format_address(BitAddress a) {
  return fmt::format("{} {}.{}", to_string(a.area), a.byte, a.bit);
}
std::string format_address(ByteAddress a) {
  return fmt::format("{} byte {}", to_string(a.area), a.byte);
}

}  // namespace hil::controllers
