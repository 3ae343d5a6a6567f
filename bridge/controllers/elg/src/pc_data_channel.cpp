// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/pc_data_channel.hpp"

#include <charconv>

namespace hil::controllers::elg {
namespace {
constexpr std::uint64_t max_digits_value = 999'999'999;
std::uint8_t to_bcd(unsigned v) noexcept {
  return static_cast<std::uint8_t>(((v / 10) % 10) << 4 | (v % 10));
}
std::optional<std::uint8_t> from_bcd(std::uint8_t b) noexcept {
  if ((b >> 4) > 9 || (b & 0x0F) > 9) return std::nullopt;
  return static_cast<std::uint8_t>((b >> 4) * 10 + (b & 0x0F));
}
void put_value(PcFrame& f, const PcValue& v) noexcept {
  f[3] = static_cast<std::uint8_t>((v.negative ? 0x80 : 0x00) | (v.decimals & 0x0F));
  std::uint64_t d = v.digits % (max_digits_value + 1);
  for (int i = 8; i >= 4; --i) {
    const auto lo = static_cast<unsigned>(d % 10);
    d /= 10;
    const auto hi = static_cast<unsigned>(d % 10);
    d /= 10;
    f[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(hi << 4 | lo);
  }
}
}  // namespace

PcFrame make_pc_request(const PcRequest& r) noexcept {
  PcFrame f{};
  f[0] = static_cast<std::uint8_t>((r.write ? 0x80 : 0x00) | (r.coding & 0x3F));
  f[1] = to_bcd(r.rel1);
  f[2] = to_bcd(r.rel2);
  put_value(f, r.value);
  return f;
}

std::expected<PcRequest, Alarm> parse_pc_request(std::span<const std::uint8_t> frame) noexcept {
  if (frame.size() != pc_frame_size) return std::unexpected(Alarm::pc_data_channel_error);
  PcRequest r;
  if ((frame[0] & 0x40) != 0 || (frame[3] & 0x70) != 0) return std::unexpected(Alarm::pc_data_channel_error);
  r.write = (frame[0] & 0x80) != 0;
  r.coding = frame[0] & 0x3F;
  const auto a1 = from_bcd(frame[1]), a2 = from_bcd(frame[2]);
  if (!a1 || !a2) return std::unexpected(Alarm::pc_data_channel_error);
  r.rel1 = *a1;
  r.rel2 = *a2;
  r.value.negative = (frame[3] & 0x80) != 0;
  r.value.decimals = frame[3] & 0x0F;
  if (r.value.decimals > 9) return std::unexpected(Alarm::pc_data_channel_error);
  std::uint64_t d = 0;
  for (std::size_t i = 4; i < pc_frame_size; ++i) {
    const auto b = from_bcd(frame[i]);
    if (!b) return std::unexpected(Alarm::pc_data_channel_error);
    d = d * 100 + *b;
  }
  if (d > max_digits_value) return std::unexpected(Alarm::pc_data_channel_error);  // a tenth digit
  r.value.digits = d;
  return r;
}

PcFrame make_pc_reply(const PcRequest& request, const PcReply& reply) noexcept {
  PcFrame f = make_pc_request(request);
  if (reply.acknowledged) f[0] |= 0x40;
  put_value(f, reply.value);
  return f;
}

std::string to_string(const PcValue& v) {
  std::string digits = std::to_string(v.digits);
  if (v.decimals > 0) {
    if (digits.size() <= v.decimals) digits.insert(0, v.decimals + 1 - digits.size(), '0');
    digits.insert(digits.size() - v.decimals, 1, '.');
  }
  return (v.negative && v.digits != 0 ? "-" : "") + digits;
}

std::optional<PcValue> parse_pc_value(std::string_view t) noexcept {
  PcValue v;
  if (!t.empty() && (t.front() == '+' || t.front() == '-')) {
    v.negative = t.front() == '-';
    t.remove_prefix(1);
  }
  if (t.empty()) return std::nullopt;
  std::uint64_t d = 0;
  int count = 0;
  bool point = false;
  for (char c : t) {
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (c < '0' || c > '9') return std::nullopt;
    d = d * 10 + static_cast<std::uint64_t>(c - '0');
    if (point) ++v.decimals;
    if (++count > 9) return std::nullopt;
  }
  if (count == 0) return std::nullopt;
  v.digits = d;
  return v;
}

}  // namespace hil::controllers::elg
