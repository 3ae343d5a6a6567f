// SPDX-License-Identifier: MIT
#include "hil/can/socketcand.hpp"

#include <array>
#include <charconv>

namespace hil::can::socketcand {

namespace {

class ParseCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "socketcand"; }
  std::string message(int ev) const override {
    switch (static_cast<ParseErrc>(ev)) {
      case ParseErrc::not_an_element:
        return "not a socketcand element (expected '< ... >')";
      case ParseErrc::empty_element:
        return "empty element '< >'";
      case ParseErrc::unknown_command:
        return "unknown command";
      case ParseErrc::missing_argument:
        return "missing argument";
      case ParseErrc::extra_argument:
        return "unexpected extra argument";
      case ParseErrc::bad_id:
        return "bad CAN id (hex, at most 8 digits, 11- or 29-bit)";
      case ParseErrc::bad_dlc:
        return "bad DLC (decimal 0..8)";
      case ParseErrc::bad_data:
        return "bad data (hex bytes, at most 8, as many as the DLC says)";
      case ParseErrc::bad_timestamp:
        return "bad timestamp (SECONDS.FRACTION)";
      case ParseErrc::bad_bus_name:
        return "bad bus name (1..16 characters)";
      case ParseErrc::element_too_long:
        return "element too long (no '>' within 256 characters)";
    }
    return "unknown socketcand parse error";
  }
};

constexpr bool is_space(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

int hex_value(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Whitespace tokenizer over the inside of an element.
class Tokens {
 public:
  explicit Tokens(std::string_view s) noexcept : s_(s) {}
  bool next(std::string_view& tok) noexcept {
    while (p_ < s_.size() && is_space(s_[p_])) ++p_;
    if (p_ >= s_.size()) return false;
    const auto b = p_;
    while (p_ < s_.size() && !is_space(s_[p_])) ++p_;
    tok = s_.substr(b, p_ - b);
    return true;
  }
  [[nodiscard]] std::string_view rest() noexcept {
    while (p_ < s_.size() && is_space(s_[p_])) ++p_;
    auto r = s_.substr(p_);
    while (!r.empty() && is_space(r.back())) r.remove_suffix(1);
    return r;
  }
  [[nodiscard]] bool at_end() noexcept {
    std::string_view t;
    auto save = p_;
    const bool more = next(t);
    p_ = save;
    return !more;
  }

 private:
  std::string_view s_;
  std::size_t p_ = 0;
};

std::expected<std::uint32_t, std::error_code> parse_hex32(std::string_view tok, std::size_t max_digits,
                                                          ParseErrc err) noexcept {
  if (tok.empty() || tok.size() > max_digits) return std::unexpected(make_error_code(err));
  std::uint32_t v = 0;
  for (char c : tok) {
    const int h = hex_value(c);
    if (h < 0) return std::unexpected(make_error_code(err));
    v = (v << 4) | static_cast<std::uint32_t>(h);
  }
  return v;
}

/// 11-bit unless written with 8 digits (socketcand's rule) or too large for 11 bits (python-can
/// 4.1 sends ids unpadded).
std::expected<void, std::error_code> parse_id(std::string_view tok, Frame& f) noexcept {
  auto v = parse_hex32(tok, 8, ParseErrc::bad_id);
  if (!v) return std::unexpected(v.error());
  if (tok.size() == 8 || *v > sff_mask) {
    if (*v > eff_mask) return std::unexpected(make_error_code(ParseErrc::bad_id));
    f.extended = true;
  }
  f.id = *v;
  return {};
}

std::expected<Timestamp, std::error_code> parse_timestamp(std::string_view tok) noexcept {
  const auto dot = tok.find('.');
  const auto sec_part = tok.substr(0, dot);
  const auto frac = dot == std::string_view::npos ? std::string_view{} : tok.substr(dot + 1);
  const auto bad = std::unexpected(make_error_code(ParseErrc::bad_timestamp));
  if (sec_part.empty() || sec_part.size() > 18) return bad;
  if (dot != std::string_view::npos && (frac.empty() || frac.size() > 9)) return bad;
  Timestamp t;
  for (char c : sec_part) {
    if (c < '0' || c > '9') return bad;
    t.sec = t.sec * 10 + (c - '0');
  }
  std::uint32_t usec = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const char c = i < frac.size() ? frac[i] : '0';
    if (c < '0' || c > '9') return bad;
    usec = usec * 10 + static_cast<std::uint32_t>(c - '0');
  }
  for (std::size_t i = 6; i < frac.size(); ++i)
    if (frac[i] < '0' || frac[i] > '9') return bad;
  t.usec = usec;
  return t;
}

std::expected<Element, std::error_code> fail(ParseErrc e) noexcept {
  return std::unexpected(make_error_code(e));
}

std::expected<Element, std::error_code> no_args(Tokens& t, Element e) noexcept {
  if (!t.at_end()) return fail(ParseErrc::extra_argument);
  return e;
}

std::expected<Element, std::error_code> parse_send(Tokens& t) noexcept {
  std::string_view tok;
  Send s;
  if (!t.next(tok)) return fail(ParseErrc::missing_argument);
  if (auto r = parse_id(tok, s.frame); !r) return std::unexpected(r.error());
  if (!t.next(tok)) return fail(ParseErrc::missing_argument);
  if (tok.size() != 1 || tok[0] < '0' || tok[0] > '8') return fail(ParseErrc::bad_dlc);
  s.frame.dlc = static_cast<std::uint8_t>(tok[0] - '0');
  std::uint8_t n = 0;
  while (t.next(tok)) {
    if (n >= s.frame.dlc) return fail(ParseErrc::bad_data);
    auto v = parse_hex32(tok, 2, ParseErrc::bad_data);
    if (!v) return std::unexpected(v.error());
    s.frame.data[n++] = static_cast<std::uint8_t>(*v);
  }
  if (n != s.frame.dlc) return fail(ParseErrc::bad_data);
  return s;
}

std::expected<Element, std::error_code> parse_frame(Tokens& t) noexcept {
  std::string_view tok;
  RxFrame r;
  if (!t.next(tok)) return fail(ParseErrc::missing_argument);
  if (auto ok = parse_id(tok, r.frame); !ok) return std::unexpected(ok.error());
  if (!t.next(tok)) return fail(ParseErrc::missing_argument);
  auto ts = parse_timestamp(tok);
  if (!ts) return std::unexpected(ts.error());
  r.time = *ts;
  // Raw mode prints the data as one hex word; BCM-style spaced bytes are accepted too.
  std::size_t nibbles = 0;
  while (t.next(tok)) {
    for (char c : tok) {
      const int h = hex_value(c);
      if (h < 0 || nibbles >= 16) return fail(ParseErrc::bad_data);
      auto& b = r.frame.data[nibbles / 2];
      b = static_cast<std::uint8_t>((nibbles % 2 == 0) ? (h << 4) : (b | h));
      ++nibbles;
    }
    if (nibbles % 2 != 0) return fail(ParseErrc::bad_data);
  }
  r.frame.dlc = static_cast<std::uint8_t>(nibbles / 2);
  return r;
}

std::expected<Element, std::error_code> parse_error(Tokens& t) noexcept {
  const auto text = t.rest();
  Tokens probe(text);
  std::string_view a, b, c;
  if (probe.next(a) && probe.next(b) && !probe.next(c)) {
    auto cls = parse_hex32(a, 8, ParseErrc::bad_id);
    auto ts = parse_timestamp(b);
    if (cls && ts && *cls <= err_mask) return ErrorFrame{make_error_frame(*cls), *ts};
  }
  try {
    return ErrorText{std::string(text)};
  } catch (...) {
    return fail(ParseErrc::element_too_long);
  }
}

constexpr std::array<std::string_view, 10> other_commands = {
    "add", "update", "delete", "filter", "muxfilter", "subscribe", "unsubscribe", "statistics", "stat", "isotpconf"};

constexpr char hex_digits[] = "0123456789ABCDEF";

void append_hex(std::string& out, std::uint32_t v, int digits) {
  for (int i = digits - 1; i >= 0; --i) out.push_back(hex_digits[(v >> (4 * i)) & 0xF]);
}

void append_timestamp(std::string& out, Timestamp t) {
  std::array<char, 24> buf{};
  auto [p, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), t.sec < 0 ? 0 : t.sec);
  (void)ec;
  out.append(buf.data(), p);
  out.push_back('.');
  std::uint32_t u = t.usec % 1000000u;
  char digits[6];
  for (int i = 5; i >= 0; --i) {
    digits[i] = static_cast<char>('0' + u % 10);
    u /= 10;
  }
  out.append(digits, 6);
}

void append_id(std::string& out, const Frame& f) {
  if (f.extended)
    append_hex(out, f.id & eff_mask, 8);
  else
    append_hex(out, f.id & sff_mask, 3);
}

}  // namespace

const std::error_category& parse_category() noexcept {
  static const ParseCategory category;
  return category;
}

std::expected<Element, std::error_code> parse_element(std::string_view text) noexcept {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  if (text.size() < 2 || text.front() != '<' || text.back() != '>') return fail(ParseErrc::not_an_element);
  if (text.size() > max_element_size) return fail(ParseErrc::element_too_long);
  const auto inner = text.substr(1, text.size() - 2);
  if (inner.find_first_of("<>") != std::string_view::npos) return fail(ParseErrc::not_an_element);
  Tokens t(inner);
  std::string_view cmd;
  if (!t.next(cmd)) return fail(ParseErrc::empty_element);
  if (cmd == "frame") return parse_frame(t);
  if (cmd == "send") return parse_send(t);
  if (cmd == "hi") return no_args(t, Hi{});
  if (cmd == "ok") return no_args(t, Ok{});
  if (cmd == "echo") return no_args(t, Echo{});
  if (cmd == "rawmode") return no_args(t, SwitchMode{Mode::raw});
  if (cmd == "bcmmode") return no_args(t, SwitchMode{Mode::bcm});
  if (cmd == "controlmode") return no_args(t, SwitchMode{Mode::control});
  if (cmd == "isotpmode") return no_args(t, SwitchMode{Mode::isotp});
  if (cmd == "error") return parse_error(t);
  if (cmd == "open") {
    std::string_view bus;
    if (!t.next(bus)) return fail(ParseErrc::missing_argument);
    if (bus.size() > max_bus_name) return fail(ParseErrc::bad_bus_name);
    if (!t.at_end()) return fail(ParseErrc::extra_argument);
    return Open{std::string(bus)};
  }
  for (auto known : other_commands)
    if (cmd == known) return Other{std::string(cmd), std::string(t.rest())};
  return fail(ParseErrc::unknown_command);
}

bool format_rx_frame(std::string& out, const Frame& frame, Timestamp time) {
  if (frame.rtr) return false;
  if (frame.error) {
    format_error_frame(out, frame.id, time);
    return true;
  }
  out.append("< frame ");
  append_id(out, frame);
  out.push_back(' ');
  append_timestamp(out, time);
  out.push_back(' ');
  for (auto b : frame.payload()) append_hex(out, b, 2);
  out.append(" >");
  return true;
}

bool format_send(std::string& out, const Frame& frame) {
  if (frame.rtr || frame.error || frame.dlc > 8) return false;
  out.append("< send ");
  append_id(out, frame);
  out.push_back(' ');
  out.push_back(static_cast<char>('0' + frame.dlc));
  for (auto b : frame.payload()) {
    out.push_back(' ');
    append_hex(out, b, 2);
  }
  out.append(" >");
  return true;
}

void format_error_frame(std::string& out, std::uint32_t error_class, Timestamp time) {
  out.append("< error ");
  append_hex(out, error_class & err_mask, (error_class & err_mask) > 0xFFF ? 8 : 3);
  out.push_back(' ');
  append_timestamp(out, time);
  out.append(" >");
}

void format_error_text(std::string& out, std::string_view text) {
  out.append("< error ");
  for (char c : text) out.push_back(c == '<' || c == '>' ? '?' : c);  // never break the framing
  out.append(" >");
}

void format_open(std::string& out, std::string_view bus) {
  out.append("< open ");
  out.append(bus);
  out.append(" >");
}

void format_mode(std::string& out, Mode mode) {
  switch (mode) {
    case Mode::bcm:
      out.append("< bcmmode >");
      break;
    case Mode::raw:
      out.append("< rawmode >");
      break;
    case Mode::control:
      out.append("< controlmode >");
      break;
    case Mode::isotp:
      out.append("< isotpmode >");
      break;
  }
}

void format_element(std::string& out, const Element& element) {
  std::visit(
      [&out](const auto& e) {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, Hi>)
          out.append(hi_element);
        else if constexpr (std::is_same_v<T, Ok>)
          out.append(ok_element);
        else if constexpr (std::is_same_v<T, Echo>)
          out.append("< echo >");
        else if constexpr (std::is_same_v<T, Open>)
          format_open(out, e.bus);
        else if constexpr (std::is_same_v<T, SwitchMode>)
          format_mode(out, e.mode);
        else if constexpr (std::is_same_v<T, RxFrame>)
          (void)format_rx_frame(out, e.frame, e.time);
        else if constexpr (std::is_same_v<T, Send>)
          (void)format_send(out, e.frame);
        else if constexpr (std::is_same_v<T, ErrorFrame>)
          format_error_frame(out, e.frame.id, e.time);
        else if constexpr (std::is_same_v<T, ErrorText>)
          format_error_text(out, e.text);
        else if constexpr (std::is_same_v<T, Other>) {
          out.append("< ");
          out.append(e.command);
          if (!e.arguments.empty()) {
            out.push_back(' ');
            out.append(e.arguments);
          }
          out.append(" >");
        }
      },
      element);
}

void ElementSplitter::feed(std::string_view bytes) {
  if (pos_ > 0 && pos_ >= buf_.size() / 2) {
    buf_.erase(0, pos_);
    pos_ = 0;
  }
  buf_.append(bytes);
}

bool ElementSplitter::next(Item& item) {
  item = {};
  for (;;) {
    const auto open = buf_.find('<', pos_);
    if (open == std::string::npos) {
      skipped_ += buf_.size() - pos_;
      buf_.clear();
      pos_ = 0;
      return false;
    }
    skipped_ += open - pos_;
    pos_ = open;
    const auto end = buf_.find_first_of("<>", open + 1);
    if (end == std::string::npos) {
      if (buf_.size() - open > max_element_size) {
        // Unterminated and already too long: drop it, report once.
        skipped_ += buf_.size() - open;
        buf_.clear();
        pos_ = 0;
        item.error = make_error_code(ParseErrc::element_too_long);
        return true;
      }
      return false;
    }
    if (buf_[end] == '<') {  // an unterminated element followed by a new one: garbage
      skipped_ += end - open;
      pos_ = end;
      continue;
    }
    pos_ = end + 1;
    if (end + 1 - open > max_element_size) {
      skipped_ += end + 1 - open;
      item.error = make_error_code(ParseErrc::element_too_long);
      return true;
    }
    item.element = std::string_view(buf_).substr(open, end + 1 - open);
    return true;
  }
}

}  // namespace hil::can::socketcand
