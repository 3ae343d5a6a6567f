// SPDX-License-Identifier: MIT
#include "hil/profiles/wire.hpp"

#include <fmt/format.h>

#include <cctype>
#include <sstream>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/twos_complement.hpp"

namespace hil::profiles {
namespace {

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t') ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

bool is_io_text(std::string_view t) {
  // "00.00.0" or "<I|Q|M><src>.<byte>.<bit>"
  auto digits = [](std::string_view d, std::size_t n) {
    if (d.size() != n) return false;
    for (char c : d)
      if (c < '0' || c > '9') return false;
    return true;
  };
  if (t == "00.00.0") return true;
  if (t.size() != 7) return false;
  if (t[0] != 'I' && t[0] != 'Q' && t[0] != 'M') return false;
  return digits(t.substr(1, 1), 1) && t[2] == '.' && digits(t.substr(3, 2), 2) && t[5] == '.' && t[6] >= '0' &&
         t[6] <= '7';
}

/// Raw integer of a numeric field for word encodings (applies lsb).
std::expected<std::int64_t, std::string> raw_of(const FieldSpec& f, const FieldValue& v) {
  const auto* d = std::get_if<Decimal>(&v);
  if (!d) return std::unexpected(fmt::format("{}: '{}' is not a number", f.name, std::get<std::string>(v)));
  // The word width is checked by each encoding; the scaling itself is done in 64 bits.
  const FixedPointFormat wide{TwosComplementFormat{64, true}, f.fixed.lsb_num, f.fixed.lsb_den};
  auto raw = make_fixed_point(*d, wide);
  if (!raw) return std::unexpected(fmt::format("{}: {}", f.name, raw.error().message));
  auto back = parse_fixed_point(*raw, wide);
  if (!back || *back != *d)
    return std::unexpected(fmt::format("{}: {} is not a multiple of the unit step", f.name, d->to_string()));
  return *raw;
}

std::expected<FieldValue, std::string> from_raw(const FieldSpec& f, std::int64_t raw) {
  auto d = parse_fixed_point(raw, FixedPointFormat{TwosComplementFormat{64, true}, f.fixed.lsb_num, f.fixed.lsb_den});
  if (!d) return std::unexpected(d.error().message);
  return FieldValue{*d};
}

std::expected<std::uint64_t, std::string> parse_hex_words(std::string_view s, int max_digits) {
  std::string digits;
  for (char c : s) {
    if (c == ' ' || c == '_' || c == 'h' || c == 'H') continue;
    if (!std::isxdigit(static_cast<unsigned char>(c))) return std::unexpected(fmt::format("'{}' is not hex", s));
    digits += c;
  }
  if (digits.starts_with("0x") || digits.starts_with("0X")) digits = digits.substr(2);
  if (digits.empty() || static_cast<int>(digits.size()) > max_digits)
    return std::unexpected(fmt::format("'{}': expected up to {} hex digits", s, max_digits));
  return std::stoull(digits, nullptr, 16);
}

std::string hex_word_text(std::uint64_t w, int digits) {
  if (digits == 8) return fmt::format("{:04X} {:04X}", (w >> 16) & 0xFFFFu, w & 0xFFFFu);
  return fmt::format("{:0{}X}", w, digits);
}

}  // namespace

std::string WireImage::describe() const {
  std::string s;
  if (bcd) s += fmt::format("BCD    {:04X} {:04X}\n", *bcd >> 16, *bcd & 0xFFFFu);
  if (binary) s += fmt::format("binary {:04X} {:04X}\n", *binary >> 16, *binary & 0xFFFFu);
  if (!words.empty()) {
    s += "words ";
    for (auto w : words) s += fmt::format(" {:04X}", w);
    s += "\n";
  }
  if (!text.empty() && !bcd) s += fmt::format("text   \"{}\"\n", text);
  return s;
}

std::expected<FieldValue, std::string> parse_field_input(const FieldSpec& f, std::string_view text) {
  switch (f.type) {
    case FieldType::io_address: {
      std::string t(text);
      for (auto& c : t) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      if (!is_io_text(t))
        return std::unexpected(
            fmt::format("'{}' is not an I/O address like I1.00.0, Q1.02.7, M2.02.0 or 00.00.0", text));
      return FieldValue{t};
    }
    case FieldType::reserved:
      return FieldValue{std::string(text)};
    case FieldType::hex: {
      auto v = parse_hex_words(text, f.hex_digits);
      if (!v) return std::unexpected(v.error());
      return FieldValue{Decimal{static_cast<std::int64_t>(*v), 0}};
    }
    case FieldType::bits: {
      if (f.binary_text && text.size() == f.bits.bits && text.find_first_not_of("01") == std::string_view::npos) {
        std::uint64_t w = 0;
        for (char c : text) w = (w << 1) | static_cast<std::uint64_t>(c - '0');
        return FieldValue{Decimal{static_cast<std::int64_t>(w), 0}};
      }
      if (auto d = parse_decimal(text); d) {
        if (d->scale != 0 || d->units < 0)
          return std::unexpected(fmt::format("'{}': a bit field is a non-negative integer", text));
        if (auto b = parse_bit_field(static_cast<std::uint64_t>(d->units), f.bits); !b)
          return std::unexpected(b.error().message);
        return FieldValue{*d};
      }
      // binary literal "00100010" (SINUMERIK bit MDs) or names "K|S|J"
      bool binary = !text.empty() && text.size() <= 64;
      for (char c : text)
        if (c != '0' && c != '1') binary = false;
      if (binary && text.size() == f.bits.bits) {
        std::uint64_t w = 0;
        for (char c : text) w = (w << 1) | static_cast<std::uint64_t>(c - '0');
        return FieldValue{Decimal{static_cast<std::int64_t>(w), 0}};
      }
      auto names = parse_bit_field_text(text, f.bits);
      if (!names) return std::unexpected(names.error().message);
      auto w = make_bit_field(*names, f.bits);
      if (!w) return std::unexpected(w.error().message);
      return FieldValue{Decimal{static_cast<std::int64_t>(*w), 0}};
    }
    case FieldType::number:
    case FieldType::choice: {
      auto d = parse_decimal(text);
      if (!d) return std::unexpected(d.error());
      if (f.type == FieldType::choice && d->scale != 0) {
        auto i = d->to_integer();
        if (!i) return std::unexpected(fmt::format("'{}': a choice is an integer", text));
        return FieldValue{Decimal{*i, 0}};
      }
      return FieldValue{*d};
    }
  }
  return std::unexpected(std::string("unknown field type"));
}

std::expected<ParamValue, std::string> parse_value_input(const ParamVariant& v, std::string_view text) {
  const auto parts = split_ws(text);
  std::size_t needed = 0;
  for (const auto& f : v.fields)
    if (f.type != FieldType::reserved || !f.fixed_text.empty()) ++needed;
  ParamValue out;
  std::size_t i = 0;
  for (const auto& f : v.fields) {
    if (f.type == FieldType::reserved && (f.fixed_text.empty() || parts.size() < v.fields.size())) {
      out.push_back(f.fixed_text);
      if (!f.fixed_text.empty() && i < parts.size() && parts[i] == f.fixed_text) ++i;
      continue;
    }
    if (i >= parts.size())
      return std::unexpected(fmt::format(
          "expected {} value(s) ({}), got {}", needed,
          [&] {
            std::string n;
            for (const auto& g : v.fields) n += (n.empty() ? "" : " ") + g.name;
            return n;
          }(),
          parts.size()));
    auto fv = parse_field_input(f, parts[i]);
    if (!fv) return std::unexpected(fmt::format("{}: {}", f.name, fv.error()));
    out.push_back(*fv);
    ++i;
  }
  if (i != parts.size())
    return std::unexpected(fmt::format("too many values: expected {}, got {}", needed, parts.size()));
  return out;
}

std::string value_text(const ParamVariant& v, const ParamValue& value) {
  std::string s;
  for (std::size_t i = 0; i < value.size(); ++i) {
    std::string t = to_string(value[i]);
    if (i < v.fields.size()) {
      const auto& f = v.fields[i];
      if (f.type == FieldType::hex)
        if (const auto* d = std::get_if<Decimal>(&value[i])) t = fmt::format("{:0{}X}", d->units, f.hex_digits);
      if (f.type == FieldType::reserved && t.empty()) continue;
      if (f.type == FieldType::bits && f.binary_text)
        if (auto b = make_field_text(f, value[i])) t = *b;
    }
    if (!s.empty()) s += ' ';
    s += t;
  }
  return s;
}

std::expected<std::string, std::string> make_field_text(const FieldSpec& f, const FieldValue& v) {
  switch (f.type) {
    case FieldType::io_address:
    case FieldType::reserved: {
      const auto* s = std::get_if<std::string>(&v);
      if (!s) return std::unexpected(fmt::format("{}: expected text", f.name));
      return *s;
    }
    case FieldType::hex: {
      const auto* d = std::get_if<Decimal>(&v);
      if (!d || d->scale != 0 || d->units < 0)
        return std::unexpected(fmt::format("{}: expected a non-negative integer", f.name));
      auto s = fmt::format("{:0{}X}", d->units, f.hex_digits);
      if (static_cast<int>(s.size()) > f.hex_digits)
        return std::unexpected(fmt::format("{}: {} does not fit {} hex digits", f.name, s, f.hex_digits));
      return s;
    }
    default: {
      const auto* d = std::get_if<Decimal>(&v);
      if (!d) return std::unexpected(fmt::format("{}: expected a number", f.name));
      if (f.type == FieldType::bits && f.binary_text) {
        if (d->scale != 0 || d->units < 0 || (f.bits.bits < 63 && d->units >= (std::int64_t{1} << f.bits.bits)))
          return std::unexpected(fmt::format("{}: {} does not fit {} bits", f.name, d->to_string(), f.bits.bits));
        std::string b;
        for (int i = static_cast<int>(f.bits.bits) - 1; i >= 0; --i) b += ((d->units >> i) & 1) ? '1' : '0';
        return b;
      }
      auto t = make_decimal_text(*d, f.text);
      if (!t) return std::unexpected(fmt::format("{}: {}", f.name, t.error().message));
      return *t;
    }
  }
}

std::expected<FieldValue, std::string> parse_field_text(const FieldSpec& f, std::string_view text) {
  switch (f.type) {
    case FieldType::io_address:
    case FieldType::reserved:
    case FieldType::hex:
      return parse_field_input(f, text);
    case FieldType::bits:
      if (f.binary_text) {
        if (text.size() != f.bits.bits || text.find_first_not_of("01") != std::string_view::npos)
          return std::unexpected(fmt::format("{}: '{}' is not {} binary digits", f.name, text, f.bits.bits));
        return parse_field_input(f, text);
      }
      [[fallthrough]];
    default: {
      auto d = parse_decimal_text(text, f.text);
      if (!d) return std::unexpected(fmt::format("{}: {}", f.name, d.error().message));
      return FieldValue{*d};
    }
  }
}

std::expected<WireImage, std::string> encode_value(const Profile& p, const ParamVariant& variant,
                                                   const ParamValue& value) {
  if (value.size() != variant.fields.size())
    return std::unexpected(fmt::format("expected {} field(s), got {}", variant.fields.size(), value.size()));
  WireImage img;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const auto& f = variant.fields[i];
    const Encoding enc = f.encoding.value_or(p.wire.encoding);
    switch (enc) {
      case Encoding::text: {
        auto t = make_field_text(f, value[i]);
        if (!t) return std::unexpected(t.error());
        if (t->empty() && f.type == FieldType::reserved) continue;
        if (!img.text.empty()) img.text += p.wire.separator;
        img.text += *t;
        break;
      }
      case Encoding::bcd_binary: {
        auto raw = raw_of(f, value[i]);
        if (!raw) return std::unexpected(raw.error());
        auto bcd = make_bcd(*raw, p.wire.bcd);
        if (!bcd) return std::unexpected(fmt::format("{}: BCD: {}", f.name, bcd.error().message));
        auto bin = make_twos_complement(*raw, TwosComplementFormat{p.wire.binary_bits, true});
        if (!bin) return std::unexpected(fmt::format("{}: binary: {}", f.name, bin.error().message));
        img.bcd = *bcd;
        img.binary = static_cast<std::uint32_t>(*bin);
        img.text = hex_word_text(*bcd, 8);
        img.words = {static_cast<std::uint16_t>(*bcd >> 16), static_cast<std::uint16_t>(*bcd & 0xFFFFu)};
        break;
      }
      case Encoding::kf:
      case Encoding::kh:
      case Encoding::fixed:
      case Encoding::kd:
      case Encoding::ky:
      case Encoding::byte_l:
      case Encoding::byte_r: {
        auto raw = raw_of(f, value[i]);
        if (!raw) return std::unexpected(raw.error());
        const bool wide = enc == Encoding::kd || (enc == Encoding::fixed && f.fixed.word.bits == 32);
        const bool byte = enc == Encoding::byte_l || enc == Encoding::byte_r;
        TwosComplementFormat tf{wide ? 32 : (byte ? 8 : 16), enc == Encoding::kf || enc == Encoding::kd ||
                                                                 (enc == Encoding::fixed && f.fixed.word.is_signed)};
        if (enc == Encoding::kh || enc == Encoding::ky) tf.is_signed = false;
        auto w = make_twos_complement(*raw, tf);
        if (!w) return std::unexpected(fmt::format("{}: {}", f.name, w.error().message));
        if (wide && p.wire.low_word_first) {
          img.words.push_back(static_cast<std::uint16_t>(*w & 0xFFFFu));
          img.words.push_back(static_cast<std::uint16_t>(*w >> 16));
        } else if (wide) {
          img.words.push_back(static_cast<std::uint16_t>(*w >> 16));
          img.words.push_back(static_cast<std::uint16_t>(*w & 0xFFFFu));
        } else if (enc == Encoding::byte_l) {
          img.words.push_back(static_cast<std::uint16_t>(*w << 8));
        } else {
          img.words.push_back(static_cast<std::uint16_t>(*w));
        }
        if (!img.text.empty()) img.text += p.wire.separator;
        // bytes are shown in their word position (DL 07 = "0700") so the text decodes back
        const std::uint64_t shown = enc == Encoding::byte_l ? (*w << 8) : *w;
        if (wide && p.wire.low_word_first)
          img.text += fmt::format("{:04X} {:04X}", *w & 0xFFFFu, (*w >> 16) & 0xFFFFu);
        else
          img.text += wide ? hex_word_text(*w, 8) : fmt::format("{:04X}", shown);
        break;
      }
    }
  }
  return img;
}

std::expected<ParamValue, std::string> decode_wire(const Profile& p, const ParamVariant& variant,
                                                   std::string_view wire) {
  ParamValue out;
  const Encoding enc0 = variant.fields.empty() ? p.wire.encoding : variant.fields[0].encoding.value_or(p.wire.encoding);
  if (enc0 == Encoding::text) {
    const auto parts = split_ws(wire);
    std::size_t i = 0;
    for (const auto& f : variant.fields) {
      if (f.type == FieldType::reserved && f.fixed_text.empty()) {
        out.push_back(std::string());
        continue;
      }
      if (i >= parts.size()) return std::unexpected(fmt::format("field '{}' missing in '{}'", f.name, wire));
      auto v = parse_field_text(f, parts[i++]);
      if (!v) return std::unexpected(v.error());
      out.push_back(*v);
    }
    if (i != parts.size())
      return std::unexpected(fmt::format("'{}' has {} field(s), expected {}", wire, parts.size(), i));
    return out;
  }
  if (enc0 == Encoding::bcd_binary) {
    // "8002 4537" / "BCD 80024537" = BCD word; "HEX FFFF A027" / "BIN ..." = binary word
    std::string_view w = wire;
    while (!w.empty() && w.front() == ' ') w.remove_prefix(1);
    bool binary = false;
    for (std::string_view pre : {"HEX", "hex", "BIN", "bin", "binary", "BINARY"})
      if (w.starts_with(pre)) {
        binary = true;
        w.remove_prefix(pre.size());
      }
    for (std::string_view pre : {"BCD", "bcd"})
      if (w.starts_with(pre)) w.remove_prefix(pre.size());
    auto word = parse_hex_words(w, 8);
    if (!word) return std::unexpected(word.error());
    const auto& f = variant.fields.at(0);
    std::int64_t raw = 0;
    if (binary) {
      auto r = parse_twos_complement(*word, TwosComplementFormat{p.wire.binary_bits, true});
      if (!r) return std::unexpected(r.error().message);
      raw = *r;
    } else {
      auto r = parse_bcd(static_cast<std::uint32_t>(*word), p.wire.bcd);
      if (!r) return std::unexpected(r.error().message);
      raw = *r;
    }
    auto v = from_raw(f, raw);
    if (!v) return std::unexpected(v.error());
    out.push_back(*v);
    return out;
  }
  // word encodings: hex words in order, one or two per field
  std::vector<std::uint16_t> words;
  for (auto part : split_ws(wire)) {
    auto w = parse_hex_words(part, 4);
    if (!w) return std::unexpected(w.error());
    words.push_back(static_cast<std::uint16_t>(*w));
  }
  std::size_t wi = 0;
  for (const auto& f : variant.fields) {
    const Encoding enc = f.encoding.value_or(p.wire.encoding);
    const bool wide = enc == Encoding::kd || (enc == Encoding::fixed && f.fixed.word.bits == 32);
    const std::size_t need = wide ? 2 : 1;
    if (wi + need > words.size()) return std::unexpected(fmt::format("field '{}' needs {} more word(s)", f.name, need));
    std::uint64_t w = !wide                   ? words[wi]
                      : p.wire.low_word_first ? (std::uint64_t{words[wi + 1]} << 16) | words[wi]
                                              : (std::uint64_t{words[wi]} << 16) | words[wi + 1];
    wi += need;
    TwosComplementFormat tf{wide ? 32 : 16, enc == Encoding::kf || enc == Encoding::kd ||
                                                (enc == Encoding::fixed && f.fixed.word.is_signed)};
    if (enc == Encoding::byte_l) {
      w >>= 8;
      tf = {8, false};
    } else if (enc == Encoding::byte_r) {
      w &= 0xFFu;
      tf = {8, false};
    }
    auto raw = parse_twos_complement(w, tf);
    if (!raw) return std::unexpected(raw.error().message);
    auto v = from_raw(f, *raw);
    if (!v) return std::unexpected(v.error());
    out.push_back(*v);
  }
  if (wi != words.size()) return std::unexpected(fmt::format("{} word(s) given, {} used", words.size(), wi));
  return out;
}

}  // namespace hil::profiles
