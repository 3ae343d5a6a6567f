// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_interface.hpp"

namespace hil::controllers::s5 {

using stepdir::Ip247Error;

namespace {
std::optional<std::uint32_t> to_bcd(std::uint64_t v, int digits) noexcept {
  std::uint32_t out = 0;
  for (int i = 0; i < digits; ++i) {
    out |= static_cast<std::uint32_t>(v % 10) << (4 * i);
    v /= 10;
  }
  if (v != 0) return std::nullopt;
  return out;
}
std::optional<std::uint64_t> from_bcd(std::uint32_t w, int digits) noexcept {
  std::uint64_t v = 0;
  for (int i = digits - 1; i >= 0; --i) {
    const std::uint32_t d = (w >> (4 * i)) & 0xF;
    if (d > 9) return std::nullopt;
    v = v * 10 + d;
  }
  return v;
}
}  // namespace

std::optional<std::uint32_t> encode_ip247_dd(std::int64_t v, bool bcd) noexcept {
  if (!bcd) return static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
  const std::uint64_t mag = static_cast<std::uint64_t>(v < 0 ? -v : v);
  auto d = to_bcd(mag, 7);
  if (!d) return std::nullopt;
  return *d | (v < 0 ? 0xF0000000u : 0u);
}

std::expected<std::int64_t, Ip247Error> decode_ip247_dd(std::uint32_t w, bool bcd) noexcept {
  if (!bcd) return static_cast<std::int32_t>(w);
  const std::uint32_t sign = w >> 28;
  if (sign != 0 && sign != 0xF) return std::unexpected(Ip247Error::path_not_bcd);
  auto v = from_bcd(w & 0x0FFFFFFF, 7);
  if (!v) return std::unexpected(Ip247Error::path_not_bcd);
  return sign == 0xF ? -static_cast<std::int64_t>(*v) : static_cast<std::int64_t>(*v);
}

std::optional<Ip247SpeedWord> encode_ip247_speed(std::int32_t v, bool bcd) noexcept {
  if (v < 0) return std::nullopt;
  if (!bcd) {
    if (v > 0xFFFF) return std::nullopt;
    return Ip247SpeedWord{static_cast<std::uint16_t>(v), 0};
  }
  if (v <= 9999) return Ip247SpeedWord{static_cast<std::uint16_t>(*to_bcd(static_cast<std::uint64_t>(v), 4)), 0};
  if (v % 10 != 0 || v > 99990) return std::nullopt;
  return Ip247SpeedWord{static_cast<std::uint16_t>(*to_bcd(static_cast<std::uint64_t>(v / 10), 4)), 1};
}

std::expected<std::int32_t, Ip247Error> decode_ip247_speed(Ip247SpeedWord s, bool bcd) noexcept {
  if (!bcd) return s.word;
  auto v = from_bcd(s.word, 4);
  if (!v) return std::unexpected(Ip247Error::speed_not_bcd);
  return static_cast<std::int32_t>(*v) * (s.byte == 1 ? 10 : 1);
}

std::optional<std::expected<Ip247Job, Ip247Error>> take_ip247_job(const std::vector<std::uint16_t>& db, bool bcd) {
  if (db.size() < ip247_axis_db_words) return std::nullopt;
  const std::uint16_t bits = db[4];
  Ip247Job job;
  if (bits & 0x02) {
    job.command = Ip247Command::stop;  // Stop has top priority
  } else if (bits & 0x01) {
    job.command = Ip247Command::start;
  } else if (bits & 0x04) {
    job.command = Ip247Command::forward;
  } else if (bits & 0x08) {
    job.command = Ip247Command::backward;
  } else if (bits & 0x10) {
    job.command = Ip247Command::takeover;
  } else {
    return std::nullopt;
  }
  job.ba = db[0] >> 8;
  job.byte_param = db[0] & 0xFF;
  const bool speed_ba = job.ba == 1 || job.ba == 2 || job.ba == 6 || job.ba == 7;
  if (speed_ba) {
    auto s = decode_ip247_speed({db[1], static_cast<std::uint8_t>(job.byte_param)}, bcd);
    if (!s) return std::unexpected(s.error());
    job.speed = *s;
  }
  auto v = decode_ip247_dd((static_cast<std::uint32_t>(db[2]) << 16) | db[3], bcd);
  if (!v) return std::unexpected(v.error());
  job.value = *v;
  return job;
}

void write_ip247_status(std::vector<std::uint16_t>& db, const Ip247Axis& axis, bool bcd) {
  if (db.size() < ip247_axis_db_words) db.resize(ip247_axis_db_words, 0);
  const auto put = [&db, bcd](std::size_t i, std::int64_t v) {
    // A value that cannot be converted to BCD is written in binary (as FB164 does).
    const std::uint32_t w = encode_ip247_dd(v, bcd).value_or(static_cast<std::uint32_t>(static_cast<std::int32_t>(v)));
    db[i] = static_cast<std::uint16_t>(w >> 16);
    db[i + 1] = static_cast<std::uint16_t>(w & 0xFFFF);
  };
  db[4] = 0;
  put(5, axis.actual());
  db[7] = db[8] = 0;
  put(9, axis.remaining());
  db[11] = static_cast<std::uint16_t>(((axis.ba() & 0xFF) << 8) | (axis.m_output() & 0xFF));
  db[12] = static_cast<std::uint16_t>((axis.attributes() << 8) | (axis.error() & 0xFF));
  db[13] = static_cast<std::uint16_t>((axis.waits_for_takeover() ? 1 : 0) | (axis.interrupted() ? 2 : 0));
}

}  // namespace hil::controllers::s5
