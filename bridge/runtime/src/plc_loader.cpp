// SPDX-License-Identifier: MIT
// Scenario key `plc:` (docs/scenarios.md "PLC steps").
#include "plc_loader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <limits>

namespace hil::runtime::detail {
namespace {

/// An integer as YAML writes it: decimal, 0x hex or 0b binary, optionally signed; in [lo, hi].
std::int64_t integer(const yaml::Field& f, std::int64_t lo, std::int64_t hi, std::string_view what) {
  const auto bad = [&] {
    f.fail(fmt::format("expected {} ({}..{}; decimal, 0x hex or 0b binary), got {}", what, lo, hi, f.describe()));
  };
  if (!f.node().IsScalar()) bad();
  std::string_view s = f.node().Scalar();
  bool neg = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    neg = s.front() == '-';
    s.remove_prefix(1);
  }
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    base = 16;
    s.remove_prefix(2);
  } else if (s.size() > 2 && s[0] == '0' && (s[1] == 'b' || s[1] == 'B')) {
    base = 2;
    s.remove_prefix(2);
  }
  std::int64_t v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, base);
  if (s.empty() || r.ec != std::errc{} || r.ptr != s.data() + s.size()) bad();
  if (neg) v = -v;
  if (v < lo || v > hi) bad();
  return v;
}

}  // namespace

PlcStep load_plc_step(const yaml::Field& v, std::string& name) {
  const auto actions = v.expect_map({"write", "wait", "expect"});
  if (actions.size() != 1)
    v.fail(actions.empty()
               ? "a plc step needs one of: write, wait, expect"
               : fmt::format("a plc step does one thing; this one has '{}' and '{}'", actions[0], actions[1]));
  PlcStep p;
  const std::string& action = actions.front();
  p.action =
      action == "write" ? PlcStep::Action::write : (action == "wait" ? PlcStep::Action::wait : PlcStep::Action::expect);
  const yaml::Field o = v.child(action);
  if (!o.node().IsMap())
    o.fail(fmt::format("expected a data-block operand {{db, dw, value | dd | dl | dr | bit}}, got {}", o.describe()));
  const auto keys = o.expect_map({"db", "dw", "value", "dd", "dl", "dr", "bit", "state"});
  p.operand.db = static_cast<int>(integer(o.required("db", "the data block number"), 1, 255, "a DB number"));
  p.operand.dw = static_cast<int>(integer(o.required("dw", "the data word number"), 0, 2047, "a data word number"));
  std::string kind;
  for (const auto& k : keys) {
    if (k == "db" || k == "dw" || k == "state") continue;
    if (!kind.empty())
      o.child(k).fail(
          fmt::format("one operand per plc step: '{}' and '{}' (value = word, dd = double word, dl / dr = "
                      "left / right byte, bit with state)",
                      kind, k));
    kind = k;
  }
  if (kind.empty()) o.fail("expected one of: value (word), dd (double word), dl, dr (bytes), bit (with state)");
  if (kind != "bit" && o.child("state").present()) o.child("state").fail("'state' belongs to 'bit'");
  const yaml::Field x = o.child(kind);
  using K = PlcOperand::Kind;
  if (kind == "value") {
    p.operand.kind = K::word;
    p.value = integer(x, -32768, 0xFFFF, "a data word") & 0xFFFF;
  } else if (kind == "dd") {
    p.operand.kind = K::double_word;
    if (p.operand.dw >= 2047) o.child("dw").fail("a double word needs DW dw and DW dw+1");
    p.value = integer(x, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max(),
                      "a signed 32-bit double word");
  } else if (kind == "dl" || kind == "dr") {
    p.operand.kind = kind == "dl" ? K::left_byte : K::right_byte;
    p.value = integer(x, 0, 0xFF, "a byte");
  } else {
    p.operand.kind = K::bit;
    p.operand.bit = static_cast<int>(integer(x, 0, 15, "a bit number of the data word"));
    p.value = 1;
    if (auto st = o.child("state"); st.present()) p.value = st.as_bool() ? 1 : 0;
  }
  name = fmt::format("plc {} DB{} DW{}", action, p.operand.db, p.operand.dw);
  return p;
}

}  // namespace hil::runtime::detail
