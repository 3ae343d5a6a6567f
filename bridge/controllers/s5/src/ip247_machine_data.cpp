// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_machine_data.hpp"

#include <cmath>

namespace hil::controllers::s5 {
namespace {

using stepdir::Ip247MdError;

std::int32_t dd(const std::vector<std::uint16_t>& w, std::size_t i) {
  return static_cast<std::int32_t>((static_cast<std::uint32_t>(w[i]) << 16) | w[i + 1]);
}
void put_dd(std::vector<std::uint16_t>& w, std::size_t i, std::int32_t v) {
  const auto u = static_cast<std::uint32_t>(v);
  w[i] = static_cast<std::uint16_t>(u >> 16);
  w[i + 1] = static_cast<std::uint16_t>(u & 0xFFFF);
}

}  // namespace

std::vector<std::uint16_t> make_ip247_md_db(const Ip247MachineData& md) {
  std::vector<std::uint16_t> w(ip247_md_words, 0);
  w[0] = 70;
  w[1] = 0x0044;
  w[2] = static_cast<std::uint16_t>(0x4200 | md.db);
  w[3] = static_cast<std::uint16_t>((md.module << 8) | md.axis);
  w[4] = static_cast<std::uint16_t>((static_cast<int>(md.unit) << 8) | (md.md_error & 0xFF));
  put_dd(w, 5, md.fmax_hz);
  put_dd(w, 7, md.fss_hz);
  put_dd(w, 9, md.accel_mhz_per_ms);
  w[11] = static_cast<std::uint16_t>(md.pulse_us);
  w[12] = md.positive_edge ? 0x40 : 0x00;
  w[13] = static_cast<std::uint16_t>(md.patterns);
  w[14] = static_cast<std::uint16_t>(md.pulses_per_rev);
  put_dd(w, 15, md.gear_bu_per_rev);
  put_dd(w, 17, md.jog1);
  put_dd(w, 19, md.jog2);
  put_dd(w, 21, md.incremental_speed);
  put_dd(w, 23, md.reference_speed);
  w[25] = md.reference_sync ? 0 : 1;
  w[26] = md.reference_direction > 0 ? 0x00 : 0x20;
  put_dd(w, 27, md.reference_coordinate);
  put_dd(w, 29, md.sw_start);
  put_dd(w, 31, md.sw_end);
  w[33] = md.limits_normally_closed ? 1 : 0;
  put_dd(w, 34, md.tool_offset);
  put_dd(w, 36, md.backlash);
  for (std::size_t k = 0; k < 4; ++k) put_dd(w, 38 + 2 * k, md.zero_offsets[k]);
  w[46] = md.rotary ? 0x80 : 0x00;
  w[47] = md.ag_bcd ? 1 : 0;
  return w;
}

std::expected<Ip247MachineData, Ip247MdError> parse_ip247_md_db(const std::vector<std::uint16_t>& w) {
  if (w.size() < 48 || w[0] != 70 || w[1] != 0x0044 || (w[2] >> 8) != 0x42) {
    return std::unexpected(static_cast<Ip247MdError>(1));
  }
  Ip247MachineData md;
  md.db = static_cast<std::uint8_t>(w[2] & 0xFF);
  md.module = w[3] >> 8;
  md.axis = w[3] & 0xFF;
  const int unit = w[4] >> 8;
  if (unit < 1 || unit > 3) return std::unexpected(static_cast<Ip247MdError>(11));
  md.unit = static_cast<Ip247Unit>(unit);
  md.md_error = w[4] & 0xFF;
  md.fmax_hz = dd(w, 5);
  md.fss_hz = dd(w, 7);
  md.accel_mhz_per_ms = dd(w, 9);
  md.pulse_us = static_cast<std::int16_t>(w[11]);
  if (w[12] != 0x00 && w[12] != 0x40) return std::unexpected(Ip247MdError::edge_polarity);
  md.positive_edge = w[12] == 0x40;
  md.patterns = static_cast<std::int16_t>(w[13]);
  md.pulses_per_rev = static_cast<std::int16_t>(w[14]);
  md.gear_bu_per_rev = dd(w, 15);
  md.jog1 = dd(w, 17);
  md.jog2 = dd(w, 19);
  md.incremental_speed = dd(w, 21);
  md.reference_speed = dd(w, 23);
  if (w[25] > 1 || (w[26] != 0x00 && w[26] != 0x20)) return std::unexpected(Ip247MdError::reference_direction);
  md.reference_sync = w[25] == 0;
  md.reference_direction = w[26] == 0x00 ? 1 : -1;
  md.reference_coordinate = dd(w, 27);
  md.sw_start = dd(w, 29);
  md.sw_end = dd(w, 31);
  if (w[33] > 1) return std::unexpected(Ip247MdError::limit_polarity);
  md.limits_normally_closed = w[33] == 1;
  md.tool_offset = dd(w, 34);
  md.backlash = dd(w, 36);
  for (std::size_t k = 0; k < 4; ++k) md.zero_offsets[k] = dd(w, 38 + 2 * k);
  md.rotary = w[46] == 0x80;
  md.ag_bcd = w[47] == 1;
  return md;
}

Ip247MdError check_ip247_md(const Ip247MachineData& md, int sysid_module) {
  const auto err = [](int v) { return static_cast<Ip247MdError>(v); };
  if (md.pulses_per_rev < 12 || md.pulses_per_rev > 1000) return err(5);
  if (md.patterns < 4 || md.patterns > 40 || md.pulses_per_rev % md.patterns != 0) return err(10);
  if (md.fmax_hz < 40 || md.fmax_hz > 100'000) return err(3);
  if (md.fss_hz < 1 || md.fss_hz > 10'000) return err(22);
  if (md.pulse_us < 1 || md.pulse_us > 31 || 2.0 * md.pulse_us * 1e-6 > 1.0 / md.fmax_hz) return err(2);
  if (md.gear_bu_per_rev < 12 || md.gear_bu_per_rev > 400'000 || md.gear_bu_per_rev < md.pulses_per_rev) return err(9);
  if (md.module != sysid_module) return err(12);
  // MD error 6 (a, tau) and 16 (ramp) come from the ramp generation.
  auto ramp = stepdir::Ip247Ramp::make(ip247_ramp_params(md), static_cast<std::int64_t>(std::ceil(1e9 / md.fmax_hz)));
  if (!ramp) return ramp.error();
  const Ip247Kinematics k = ip247_kinematics(md);
  for (const std::int32_t v : {md.jog1, md.jog2, md.incremental_speed}) {
    const double f = k.frequency_hz(v);
    if (v < 1 || v > 65000 || f < 1.0 || f > md.fmax_hz + 1e-9) return err(4);
  }
  const double f_ref = k.frequency_hz(md.reference_speed);
  if (md.reference_speed < 1 || md.reference_speed > 65000 || f_ref <= md.fss_hz || f_ref > md.fmax_hz + 1e-9) {
    return err(17);
  }
  const auto outside = [](std::int64_t v) { return v <= -ip247_coordinate_limit || v >= ip247_coordinate_limit; };
  if (md.rotary) {
    if (md.sw_start >= md.sw_end) return err(21);
  } else if (md.sw_start > md.sw_end || outside(md.sw_start) || outside(md.sw_end)) {
    return err(7);
  }
  if (md.reference_coordinate < md.sw_start || md.reference_coordinate > md.sw_end) return err(8);
  if (md.backlash < 0 || md.backlash > 64'999) return err(20);
  for (const std::int32_t z : md.zero_offsets) {
    if (outside(z) || outside(std::int64_t{md.sw_start} - z) || outside(std::int64_t{md.sw_end} - z)) return err(13);
  }
  if (outside(md.tool_offset) || outside(std::int64_t{md.sw_end} + md.tool_offset) ||
      outside(std::int64_t{md.sw_start} + md.tool_offset)) {
    return err(14);
  }
  return Ip247MdError::none;
}

std::int64_t Ip247Kinematics::pulses(std::int64_t v) const noexcept {
  // round(v * ppr / gear), symmetric
  // |v| < 2^31 BU and ppr <= 1000: the product fits 64 bits.
  const std::int64_t n = v * ppr;
  return (n >= 0 ? n + gear_bu / 2 : n - gear_bu / 2) / gear_bu;
}

std::int64_t Ip247Kinematics::bu(std::int64_t p) const noexcept {
  const std::int64_t n = p * gear_bu;  // |p| < 2^41 pulses, gear <= 4e5: fits
  return (n >= 0 ? n + ppr / 2 : n - ppr / 2) / ppr;
}

double Ip247Kinematics::frequency_hz(double unit_per_min) const noexcept {
  return unit_per_min * 1000.0 / 60.0 / resolution_bu();
}

Ip247Kinematics ip247_kinematics(const Ip247MachineData& md) noexcept {
  return {.gear_bu = md.gear_bu_per_rev, .ppr = md.pulses_per_rev, .f_max_hz = static_cast<double>(md.fmax_hz)};
}

stepdir::Ip247RampParams ip247_ramp_params(const Ip247MachineData& md) noexcept {
  return {.f_max_hz = static_cast<double>(md.fmax_hz),
          .f_ss_hz = static_cast<double>(md.fss_hz),
          .accel_hz_per_s = static_cast<double>(md.accel_mhz_per_ms)};
}

}  // namespace hil::controllers::s5
