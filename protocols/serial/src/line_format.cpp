// SPDX-License-Identifier: MIT
#include "hil/serial/line_format.hpp"

#include <fmt/format.h>
#include <charconv>

namespace hil::serial {

std::string LineFormat::describe() const {
  const char p = parity == Parity::none ? 'N' : parity == Parity::even ? 'E' : 'O';
  const char* s = stop_bits == StopBits::one ? "1" : stop_bits == StopBits::two ? "2" : "1.5";
  const char* fl = flow == FlowControl::none ? "" : flow == FlowControl::rts_cts ? " rts/cts" : " xon/xoff";
  return fmt::format("{} {}{}{}{}", baud, static_cast<int>(data_bits), p, s, fl);
}

std::expected<LineFormat, FormatError> parse_char_format(std::string_view text, LineFormat base) {
  const auto bad = [&] {
    return std::unexpected(
        FormatError{fmt::format("character format '{}' not understood: expected <data bits 7|8><parity N|E|O><stop "
                                "bits 1|1.5|2>, e.g. 7E2 or 8N1",
                                text)});
  };
  if (text.size() < 3) return bad();
  if (text[0] != '7' && text[0] != '8') return bad();
  base.data_bits = static_cast<std::uint8_t>(text[0] - '0');
  switch (text[1]) {
    case 'N':
    case 'n':
      base.parity = Parity::none;
      break;
    case 'E':
    case 'e':
      base.parity = Parity::even;
      break;
    case 'O':
    case 'o':
      base.parity = Parity::odd;
      break;
    default:
      return bad();
  }
  const auto stop = text.substr(2);
  if (stop == "1")
    base.stop_bits = StopBits::one;
  else if (stop == "1.5")
    base.stop_bits = StopBits::one_and_half;
  else if (stop == "2")
    base.stop_bits = StopBits::two;
  else
    return bad();
  return validate(base);
}

std::expected<LineFormat, FormatError> validate(const LineFormat& f) {
  if (f.baud < 110 || f.baud > 115200)
    return std::unexpected(FormatError{fmt::format("baud rate {} out of range: allowed 110..115200", f.baud)});
  if (f.data_bits != 7 && f.data_bits != 8)
    return std::unexpected(
        FormatError{fmt::format("{} data bits not supported: use 7 or 8", static_cast<int>(f.data_bits))});
  if (f.flow == FlowControl::xon_xoff && f.xon == f.xoff)
    return std::unexpected(FormatError{fmt::format("XON and XOFF are both 0x{:02X}: they must differ", f.xon)});
  return f;
}

std::expected<FlowControl, FormatError> parse_flow_control(std::string_view text) {
  if (text == "none") return FlowControl::none;
  if (text == "rtscts" || text == "rts/cts" || text == "hardware") return FlowControl::rts_cts;
  if (text == "xonxoff" || text == "xon/xoff" || text == "software") return FlowControl::xon_xoff;
  return std::unexpected(FormatError{fmt::format("flow control '{}' unknown: use none, rtscts or xonxoff", text)});
}

}  // namespace hil::serial
