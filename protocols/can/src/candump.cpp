// SPDX-License-Identifier: MIT
#include "hil/can/candump.hpp"

#include <charconv>

namespace hil::can::candump {

namespace {

class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "candump"; }
  std::string message(int ev) const override {
    switch (static_cast<ParseErrc>(ev)) {
      case ParseErrc::missing_separator:
        return "missing '#' between CAN id and data (expected e.g. 123#DEADBEEF)";
      case ParseErrc::bad_id:
        return "bad CAN id (3 hex digits for 11-bit, 8 for 29-bit)";
      case ParseErrc::bad_data:
        return "bad data (up to 8 bytes as pairs of hex digits, '.' allowed between bytes)";
      case ParseErrc::bad_rtr_length:
        return "bad remote frame length (use #R or #R0..#R8)";
      case ParseErrc::fd_not_supported:
        return "CAN FD frames (##) are not supported; classic CAN only";
      case ParseErrc::bad_timestamp:
        return "bad timestamp (expected '(SECONDS.FRACTION)')";
      case ParseErrc::bad_interface:
        return "missing or overlong interface name";
      case ParseErrc::trailing_garbage:
        return "unexpected text after the frame";
    }
    return "unknown candump parse error";
  }
};

int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::unexpected<std::error_code> fail(ParseErrc e) noexcept {
  return std::unexpected(make_error_code(e));
}

constexpr char hex_digits[] = "0123456789ABCDEF";
void append_hex(std::string& out, std::uint32_t v, int digits) {
  for (int i = digits - 1; i >= 0; --i) out.push_back(hex_digits[(v >> (4 * i)) & 0xF]);
}

}  // namespace

const std::error_category& parse_category() noexcept {
  static const Category c;
  return c;
}

std::expected<Frame, std::error_code> parse_frame_spec(std::string_view spec) noexcept {
  const auto hash = spec.find('#');
  if (hash == std::string_view::npos) return fail(ParseErrc::missing_separator);
  const auto id_text = spec.substr(0, hash);
  auto rest = spec.substr(hash + 1);
  if (id_text.size() != 3 && id_text.size() != 8) return fail(ParseErrc::bad_id);
  std::uint32_t can_id = 0;
  for (char c : id_text) {
    const int h = hex_value(c);
    if (h < 0) return fail(ParseErrc::bad_id);
    can_id = (can_id << 4) | static_cast<std::uint32_t>(h);
  }
  Frame f;
  if (id_text.size() == 3) {
    if (can_id > sff_mask) return fail(ParseErrc::bad_id);
    f.id = can_id;
  } else if (can_id & err_flag) {
    f.error = true;
    f.id = can_id & err_mask;
  } else {
    if (can_id > eff_mask) return fail(ParseErrc::bad_id);
    f.extended = true;
    f.id = can_id;
  }
  if (!rest.empty() && rest.front() == '#') return fail(ParseErrc::fd_not_supported);
  if (!rest.empty() && (rest.front() == 'R' || rest.front() == 'r')) {
    if (f.error) return fail(ParseErrc::bad_data);
    f.rtr = true;
    rest.remove_prefix(1);
    if (rest.empty()) return f;
    if (rest.size() != 1 || rest[0] < '0' || rest[0] > '8') return fail(ParseErrc::bad_rtr_length);
    f.dlc = static_cast<std::uint8_t>(rest[0] - '0');
    return f;
  }
  std::size_t n = 0;
  for (std::size_t i = 0; i < rest.size();) {
    if (rest[i] == '.') {
      ++i;
      continue;
    }
    if (rest[i] == '_') return fail(ParseErrc::bad_data);
    if (i + 1 >= rest.size() || n >= 8) return fail(ParseErrc::bad_data);
    const int hi = hex_value(rest[i]);
    const int lo = hex_value(rest[i + 1]);
    if (hi < 0 || lo < 0) return fail(ParseErrc::bad_data);
    f.data[n++] = static_cast<std::uint8_t>((hi << 4) | lo);
    i += 2;
  }
  f.dlc = static_cast<std::uint8_t>(n);
  return f;
}

void format_frame_spec(std::string& out, const Frame& frame) {
  if (frame.error)
    append_hex(out, err_flag | (frame.id & err_mask), 8);
  else if (frame.extended)
    append_hex(out, frame.id & eff_mask, 8);
  else
    append_hex(out, frame.id & sff_mask, 3);
  out.push_back('#');
  if (frame.rtr) {
    out.push_back('R');
    if (frame.dlc > 0) out.push_back(static_cast<char>('0' + (frame.dlc > 8 ? 8 : frame.dlc)));
    return;
  }
  for (auto b : frame.payload()) append_hex(out, b, 2);
}

std::string format_frame_spec(const Frame& frame) {
  std::string s;
  format_frame_spec(s, frame);
  return s;
}

std::expected<LogRecord, std::error_code> parse_log_line(std::string_view line) noexcept {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
  if (line.size() < 3 || line.front() != '(') return fail(ParseErrc::bad_timestamp);
  const auto close = line.find(')');
  if (close == std::string_view::npos) return fail(ParseErrc::bad_timestamp);
  const auto ts_text = line.substr(1, close - 1);
  const auto dot = ts_text.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot > 18 || ts_text.size() - dot - 1 == 0 ||
      ts_text.size() - dot - 1 > 9)
    return fail(ParseErrc::bad_timestamp);
  LogRecord r;
  for (char c : ts_text.substr(0, dot)) {
    if (c < '0' || c > '9') return fail(ParseErrc::bad_timestamp);
    r.time.sec = r.time.sec * 10 + (c - '0');
  }
  const auto frac = ts_text.substr(dot + 1);
  std::uint32_t usec = 0;
  for (std::size_t i = 0; i < frac.size(); ++i) {
    if (frac[i] < '0' || frac[i] > '9') return fail(ParseErrc::bad_timestamp);
    if (i < 6) usec = usec * 10 + static_cast<std::uint32_t>(frac[i] - '0');
  }
  for (std::size_t i = frac.size(); i < 6; ++i) usec *= 10;
  r.time.usec = usec;
  auto rest = line.substr(close + 1);
  if (rest.empty() || rest.front() != ' ') return fail(ParseErrc::bad_interface);
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  const auto sp = rest.find(' ');
  if (sp == std::string_view::npos || sp == 0 || sp > 15) return fail(ParseErrc::bad_interface);
  try {
    r.interface.assign(rest.substr(0, sp));
  } catch (...) {
    return fail(ParseErrc::bad_interface);
  }
  rest = rest.substr(sp + 1);
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  const auto sp2 = rest.find(' ');
  const auto spec = rest.substr(0, sp2);
  if (sp2 != std::string_view::npos) {
    auto tail = rest.substr(sp2);
    while (!tail.empty() && tail.front() == ' ') tail.remove_prefix(1);
    if (tail != "T" && tail != "R") return fail(ParseErrc::trailing_garbage);
  }
  auto f = parse_frame_spec(spec);
  if (!f) return std::unexpected(f.error());
  r.frame = *f;
  return r;
}

void format_log_line(std::string& out, const LogRecord& record) {
  out.push_back('(');
  char buf[24];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, record.time.sec < 0 ? 0 : record.time.sec);
  (void)ec;
  out.append(buf, p);
  out.push_back('.');
  std::uint32_t u = record.time.usec % 1000000u;
  char digits[6];
  for (int i = 5; i >= 0; --i) {
    digits[i] = static_cast<char>('0' + u % 10);
    u /= 10;
  }
  out.append(digits, 6);
  out.append(") ");
  out.append(record.interface);
  out.push_back(' ');
  format_frame_spec(out, record.frame);
}

}  // namespace hil::can::candump
