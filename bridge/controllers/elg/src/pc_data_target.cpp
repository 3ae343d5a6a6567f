// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/pc_data_target.hpp"

#include <algorithm>

namespace hil::controllers::elg {
namespace {

PcReply refused(Alarm alarm) {
  PcReply r;
  r.alarm = alarm;  // not performed, but acknowledged (12.5)
  return r;
}
PcReply done(PcValue value) {
  PcReply r;
  r.performed = true;
  r.value = value;
  return r;
}

/// An MD word as tape text ("-1234") from a value without decimals.
std::string word_text(const PcValue& v) {
  return (v.negative && v.digits != 0 ? "-" : "") + std::to_string(v.digits);
}

std::optional<PcValue> word_value(const std::string& text) {
  auto v = parse_pc_value(text);
  if (!v || v->decimals != 0) return std::nullopt;
  return v;
}

/// "00010010" <-> the value with the digits 10010 (eight digits 0/1, bit 7 first).
std::optional<PcValue> bits_value(const std::string& text) {
  if (text.size() != 8 || !std::all_of(text.begin(), text.end(), [](char c) { return c == '0' || c == '1'; }))
    return std::nullopt;
  return parse_pc_value(text);
}
std::optional<std::string> bits_text(const PcValue& v) {
  if (v.negative || v.decimals != 0 || v.digits > 11111111) return std::nullopt;
  std::string s = std::to_string(v.digits);
  if (s.find_first_not_of("01") != std::string::npos) return std::nullopt;
  return std::string(8 - s.size(), '0') + s;
}

PcReply datum_request(const PcRequest& r, PcDataTarget& t, DatumKind kind, bool bits) {
  const int number = r.address();
  const auto current = t.datum(kind, number);
  if (!current) return refused(Alarm::pc_datum_not_present);
  if (!r.write) {
    const auto v = bits ? bits_value(*current) : word_value(*current);
    if (!v) return refused(Alarm::pc_datum_not_present);  // a bit datum asked for as a word
    return done(*v);
  }
  // "$": MD and SD are not written while coupling ON; [I] refused as an impermissible transfer.
  if (t.coupled()) return refused(Alarm::pc_data_channel_error);
  std::optional<std::string> text;
  if (bits)
    text = bits_text(r.value);
  else if (r.value.decimals == 0)
    text = word_text(r.value);
  if (!text) return refused(Alarm::pc_data_channel_error);
  if (!t.store_datum(kind, number, *text)) return refused(Alarm::pc_data_channel_error);
  return done(r.value);
}

}  // namespace

PcReply handle_pc_request(const PcRequest& r, PcDataTarget& t) {
  switch (static_cast<PcCoding>(r.coding)) {
    case PcCoding::r_parameter: {
      if (r.rel2 != 0) return refused(Alarm::pc_datum_not_present);
      if (!r.write) {
        const auto v = t.r_parameter(r.rel1);
        return v ? done(*v) : refused(Alarm::pc_datum_not_present);
      }
      // +-99999.999 with a variable decimal point: eight digits at most.
      if (r.value.digits > 99'999'999) return refused(Alarm::pc_data_channel_error);
      if (!t.r_parameter(r.rel1)) return refused(Alarm::pc_datum_not_present);
      if (!t.store_r_parameter(r.rel1, r.value)) return refused(Alarm::pc_data_channel_error);
      return done(r.value);
    }
    case PcCoding::word:
      if (r.rel2 <= 49) return datum_request(r, t, DatumKind::machine_data, false);
      if (r.rel2 >= 80 && r.rel2 <= 89) {
        if (r.write) return refused(Alarm::pc_data_channel_error);  // service data are read only
        const auto v = t.service_datum(r.address());
        return v ? done(*v) : refused(Alarm::pc_datum_not_present);
      }
      return refused(Alarm::pc_datum_not_present);
    case PcCoding::actual_value: {
      if (r.write) return refused(Alarm::pc_data_channel_error);
      if (r.rel2 != 0 || r.rel1 < 1 || r.rel1 > 4) return refused(Alarm::pc_datum_not_present);
      const auto v = t.actual_value(r.rel1);
      return v ? done(*v) : refused(Alarm::pc_datum_not_present);
    }
    case PcCoding::alarms: {
      if (r.write) return refused(Alarm::pc_data_channel_error);
      if (r.rel2 != 0 || r.rel1 < 1) return refused(Alarm::pc_datum_not_present);
      const auto pending = t.alarms();
      const std::size_t slot = static_cast<std::size_t>(r.rel1 - 1);
      PcValue v;
      v.digits = slot < pending.size() ? static_cast<std::uint64_t>(pending[slot]) : 0;  // 0: slot empty
      return done(v);
    }
    case PcCoding::md_bits:
      if (r.rel2 < 50 || r.rel2 > 69) return refused(Alarm::pc_datum_not_present);
      return datum_request(r, t, DatumKind::machine_data, true);
    case PcCoding::sd_bits:
      if (r.rel2 < 50 || r.rel2 > 59) return refused(Alarm::pc_datum_not_present);
      return datum_request(r, t, DatumKind::setting_data, true);
  }
  return refused(Alarm::pc_data_channel_error);  // a coding the table does not list
}

}  // namespace hil::controllers::elg
