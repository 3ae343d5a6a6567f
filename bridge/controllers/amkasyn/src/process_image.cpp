// SPDX-License-Identifier: MIT
// Data holders (digest §1.6): which (address, offset) pairs exist and what they read/write.
#include "hil/controllers/amkasyn/process_image.hpp"

namespace hil::controllers::amkasyn {
namespace {

bool aw(std::uint8_t a) {
  return a >= 1 && a <= 8;
}

}  // namespace

bool valid_source(Holder h) noexcept {
  switch (h.address) {
    case 0:
      return h.offset == 0 || h.offset == 1 || h.offset == 3 || h.offset == 5 || h.offset == 7 || h.offset == 16 ||
             h.offset == 18 || h.offset == 20 || h.offset == 22;
    case 128:
      return h.offset % 2 == 0 && h.offset <= 126;
    case 129:
      return h.offset % 4 == 0 && h.offset <= 124;
    case 130:
      return h.offset % 2 == 0 && h.offset <= 30;
    case 131:
      return h.offset % 4 == 0 && h.offset <= 28;
    case 255:
      return h.offset < max_sf;
    default:
      return aw(h.address) && (h.offset == 2 || h.offset == 3 || h.offset == 5 || h.offset == 19 || h.offset == 21);
  }
}

bool valid_sink(Holder h) noexcept {
  switch (h.address) {
    case 0:
      return h.offset == 0;
    case 64:
      return h.offset <= 3;
    case 128:
      return h.offset % 2 == 0 && h.offset <= 126;
    case 129:
      return h.offset % 4 == 0 && h.offset <= 124;
    case 255:
      return h.offset == 0;
    default:
      return aw(h.address) && (h.offset == 4 || h.offset == 16);
  }
}

HolderValue read_source(const ProcessImage& im, const std::array<std::int32_t, max_sf>& links, Holder h) noexcept {
  auto lo = [](std::int32_t v) { return HolderValue{static_cast<std::int16_t>(v & 0xFFFF), false}; };
  switch (h.address) {
    case 0:
      if (h.offset >= 16) return {im.az[static_cast<std::size_t>((h.offset - 16) / 2 % 4)], true};
      if (h.offset == 0) return {0, true};
      return {static_cast<std::int16_t>(
                  static_cast<std::uint32_t>(im.az[static_cast<std::size_t>((h.offset - 1) / 2 % 4)]) >> 16),
              false};
    case 128:
      return {im.mw(h.offset), false};
    case 129:
      return {im.md(h.offset), true};
    case 130:
      return {im.ew(h.offset), false};
    case 131:
      return {im.ed(h.offset), true};
    case 255:
      return {links[h.offset % max_sf], true};
    default:
      break;
  }
  if (!aw(h.address)) return {0, true};
  const DriveChannels& d = im.aw[h.address - 1u];
  switch (h.offset) {
    case 2:
      return {d.message16, false};
    case 3:
      return lo(d.message32);
    case 5:
      return lo(d.position_feedback);
    case 19:
      return {d.message32, true};
    case 21:
      return {d.position_feedback, true};
    default:
      return {0, true};
  }
}

std::int32_t read_sink(const ProcessImage& im, Holder h) noexcept {
  switch (h.address) {
    case 64:
      return im.analog_out[h.offset % 4u];
    case 128:
      return im.mw(h.offset);
    case 129:
      return im.md(h.offset);
    default:
      break;
  }
  if (!aw(h.address)) return 0;
  const DriveChannels& d = im.aw[h.address - 1u];
  return h.offset == 4 ? d.swq1 : d.swq2;
}

void write_sink(ProcessImage& im, Holder h, std::int32_t v) noexcept {
  switch (h.address) {
    case 0:
    case 255:
      return;  // no sink / internal only (the link array holds it)
    case 64:
      im.analog_out[h.offset % 4u] = v;
      return;
    case 128:
      im.set_mw(h.offset, v);
      return;
    case 129:
      im.set_md(h.offset, v);
      return;
    default:
      break;
  }
  if (!aw(h.address)) return;
  DriveChannels& d = im.aw[h.address - 1u];
  if (h.offset == 4) {
    d.swq1 = static_cast<std::int16_t>(v & 0xFFFF);
    d.swq1_written = true;
  } else {
    d.swq2 = v;
    d.swq2_written = true;
  }
}

}  // namespace hil::controllers::amkasyn
