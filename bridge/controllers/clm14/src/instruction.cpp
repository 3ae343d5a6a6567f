// SPDX-License-Identifier: MIT
// CLM1.4 program-line parser (manual §5.7 syntax figures and the §9.2 data-format table).
#include "hil/controllers/clm14/instruction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace hil::controllers::clm14 {

namespace {

constexpr std::array<std::string_view, op_count> names{
    "ACC", "AEA", "AEO", "AKN", "AKP", "APE", "BAC", "BCE", "BIC", "BIO", "BPA", "CID", "CIO", "CLC",
    "CON", "COU", "CPJ", "CPL", "CPS", "CST", "CVT", "EOS", "FAK", "FOL", "FUN", "HOM", "JMP", "JSR",
    "JST", "JTK", "LMK", "LML", "LMR", "MAT", "MLO", "MLT", "NOP", "PBK", "POA", "POI", "PSA", "PSI",
    "REP", "RMI", "RSV", "RTM", "RTS", "SAC", "SET", "SRM", "SRP", "TXT", "VCC", "VEO", "WAI"};

struct Fail {
  ClmError error;
  std::string why;
};

/// Operand kinds of the table below.
enum class K : std::uint8_t {
  axis,     // 1..4 or Vnnn (error 16)
  target,   // line 0000..2999 or Vnnn (error 0E)
  num,      // signed/unsigned number or Vnnn
  count,    // COU/BAC offset: "+00000", "-00012", "000000" (reset)
  bit,      // Ix.yy.z
  bit2,     // second bit
  byte,     // Ix.yy
  byte2,    // second byte
  pattern,  // 8 chars 0/1/2
  var,      // Vnnn written/compared (instruction.var)
  text,     // rest of line (TXT) / RSV flags
};

struct Layout {
  Op op;
  std::vector<K> ops;
};

// Operand order per command. FOL, FUN, LMK, LMR, MLO and MLT lost their syntax figures: their
// layouts are decisions (docs/clm14.md, "Decisions").
const std::vector<Layout>& layouts() {
  static const std::vector<Layout> t{
      {Op::acc, {K::axis, K::num, K::num}},
      {Op::aea, {K::bit, K::num}},
      {Op::aeo, {K::axis, K::num, K::num, K::num, K::num}},
      {Op::akn, {K::bit, K::num}},
      {Op::akp, {K::byte, K::pattern}},
      {Op::ape, {K::byte, K::pattern}},
      {Op::bac, {K::target, K::count, K::num}},
      {Op::bce, {K::target, K::bit, K::num}},
      {Op::bic, {K::num, K::num, K::bit, K::num, K::num}},
      {Op::bio, {K::target, K::byte, K::byte2, K::pattern}},
      {Op::bpa, {K::target, K::byte, K::pattern}},
      {Op::cid, {K::var, K::num, K::num}},
      {Op::cio, {K::bit, K::bit2, K::num}},
      {Op::clc, {K::target}},
      {Op::con, {K::axis, K::num, K::num}},
      {Op::cou, {K::count, K::bit, K::num}},
      {Op::cpl, {K::axis}},
      {Op::cst, {K::num, K::num}},
      {Op::cvt, {K::var, K::byte, K::num, K::num}},
      {Op::eos, {}},
      {Op::fak, {K::num, K::num}},  // axis 1..4 or 5 = master encoder 1 (checked below)
      {Op::fol, {K::axis, K::num, K::num}},
      {Op::hom, {K::axis}},
      {Op::jmp, {K::target}},
      {Op::jsr, {K::target}},
      {Op::jst, {K::target}},
      {Op::jtk, {K::target, K::num}},
      {Op::lmk, {K::axis, K::num, K::num}},
      {Op::lml, {K::axis, K::num}},
      {Op::lmr, {K::axis, K::num, K::num, K::num}},
      {Op::mlo, {K::axis, K::num, K::bit}},
      {Op::mlt, {K::axis, K::num, K::bit}},
      {Op::nop, {}},
      {Op::pbk, {K::axis}},
      {Op::poa, {K::axis, K::num, K::num}},
      {Op::poi, {K::axis, K::num, K::num}},
      {Op::psa, {K::axis, K::num, K::num}},
      {Op::psi, {K::axis, K::num, K::num}},
      {Op::rep, {K::target, K::axis, K::num}},
      {Op::rmi, {K::axis, K::num, K::bit}},
      {Op::rsv, {K::num, K::num, K::text}},
      {Op::rtm, {K::axis, K::num}},
      {Op::rts, {}},
      {Op::sac, {K::axis, K::num, K::num}},
      {Op::srm, {K::axis, K::num, K::num, K::bit}},
      {Op::srp, {K::axis, K::num, K::num, K::var, K::byte}},
      {Op::vcc, {K::axis, K::num, K::num, K::num, K::num}},
      {Op::veo, {K::axis, K::num, K::num, K::num, K::num}},
      {Op::wai, {K::num}},
  };
  return t;
}

std::expected<Num, Fail> num_of(std::string_view t) {
  Num n;
  std::string_view v = t;
  bool neg = false;
  if (!v.empty() && (v.front() == '+' || v.front() == '-')) {
    neg = v.front() == '-';
    v.remove_prefix(1);
  }
  if (!v.empty() && v.front() == 'V') {
    if (v.size() != 4 || !std::all_of(v.begin() + 1, v.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return std::unexpected(
          Fail{ClmError::invalid_program_command, fmt::format("'{}' is not a variable V000..V999", t)});
    n.var = static_cast<std::int16_t>((v[1] - '0') * 100 + (v[2] - '0') * 10 + (v[3] - '0'));
    n.negate = neg;
    return n;
  }
  auto m = parse_micro(t);
  if (!m) return std::unexpected(Fail{ClmError::invalid_program_command, fmt::format("'{}' is not a number", t)});
  n.value = *m;
  return n;
}

std::expected<std::int16_t, Fail> var_of(std::string_view t) {
  auto n = num_of(t);
  if (!n || !n->is_var() || n->negate || t.front() == '+')
    return std::unexpected(Fail{ClmError::invalid_program_command, fmt::format("'{}' is not a variable Vnnn", t)});
  return n->var;
}

std::vector<std::string_view> split(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && s[i] == ' ') ++i;
    const std::size_t b = i;
    while (i < s.size() && s[i] != ' ') ++i;
    if (i > b) out.push_back(s.substr(b, i - b));
  }
  return out;
}

/// Puts spaces around a comparison/assignment operator so "V600>=+V601" splits into 3 tokens.
std::string spaced_operators(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const bool opc = c == '<' || c == '>' || c == '=';
    if (opc && (i == 0 || !(s[i - 1] == '<' || s[i - 1] == '>' || s[i - 1] == '='))) out += ' ';
    out += c;
    if (opc && (i + 1 == s.size() || !(s[i + 1] == '<' || s[i + 1] == '>' || s[i + 1] == '='))) out += ' ';
  }
  return out;
}

std::expected<Cmp, Fail> cmp_of(std::string_view t) {
  if (t == "=") return Cmp::eq;
  if (t == "<>") return Cmp::ne;
  if (t == "<") return Cmp::lt;
  if (t == ">") return Cmp::gt;
  if (t == "<=") return Cmp::le;
  if (t == ">=") return Cmp::ge;
  return std::unexpected(Fail{ClmError::invalid_program_command, fmt::format("'{}' is not = <> < > <= >=", t)});
}

std::expected<void, Fail> check_num_ranges(const Instruction& in, const std::vector<K>& ks) {
  std::size_t ni = 0;
  for (K k : ks) {
    if (k != K::axis && k != K::target && k != K::num && k != K::count) continue;
    const Num& n = in.n[ni++];
    if (n.is_var()) continue;
    if (k == K::axis && (n.value % micro_one != 0 || n.value < micro_one || n.value > 4 * micro_one))
      return std::unexpected(Fail{ClmError::axis_number, fmt::format("axis {} is not 1..4", to_double(n.value))});
    if (k == K::target && (n.value % micro_one != 0 || n.value < 0))
      return std::unexpected(Fail{ClmError::invalid_block_number, "line target is not a line number"});
    if (k == K::target && n.value > 2999 * micro_one)
      return std::unexpected(
          Fail{ClmError::invalid_block_number, fmt::format("line {} is beyond 2999", n.value / micro_one)});
  }
  return {};
}

std::expected<Instruction, Fail> parse(std::string_view text) {
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  const std::string_view mne = text.substr(0, 3);
  const auto it = std::find(names.begin(), names.end(), mne);
  if (text.size() < 3 || it == names.end() || (text.size() > 3 && text[3] != ' '))
    return std::unexpected(Fail{ClmError::invalid_program_command, "not a CLM command (ACC ... WAI)"});
  Instruction in;
  in.op = static_cast<Op>(it - names.begin());
  std::string_view rest = text.size() > 4 ? text.substr(4) : std::string_view{};
  const auto bad = [](std::string why) {
    return std::unexpected(Fail{ClmError::invalid_program_command, std::move(why)});
  };
  switch (in.op) {
    case Op::txt: {
      // "TXT m 16chars": the text keeps its spaces (ASCII 32..95 except '$' and '\').
      while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
      if (rest.empty() || rest[0] < '0' || rest[0] > '2' || (rest.size() > 1 && rest[1] != ' '))
        return bad("TXT mode must be 0, 1 or 2");
      in.n[0].value = (rest[0] - '0') * micro_one;
      in.text = rest.size() > 2 ? std::string(rest.substr(2)) : std::string{};
      if (in.text.size() > 16) return bad("TXT text longer than 16 characters");
      for (char c : in.text)
        if (c < 32 || c > 95 || c == '$' || c == '\\') return bad(fmt::format("TXT character '{}' not allowed", c));
      in.text.resize(16, ' ');
      return in;
    }
    case Op::fun: {
      // "FUN ccccccc" [decided]: one digit per channel - axes 1..4, master encoder 1, master
      // encoder 2, material through the tool - each 0 (buffer, clear, restart), 1 (clear and
      // restart, keep the buffer) or 2 (no change).
      const auto tok = split(rest);
      if (tok.size() != 1 || tok[0].size() != 7 || tok[0].find_first_not_of("012") != std::string_view::npos)
        return bad("FUN expects 7 channel digits 0/1/2 (axes 1-4, encoder 1, encoder 2, material through the tool)");
      for (std::size_t i = 0; i < 7; ++i) in.pattern[i] = static_cast<std::uint8_t>(tok[0][i] - '0');
      return in;
    }
    case Op::set:
    case Op::mat:
    case Op::cpj:
    case Op::cps: {
      const std::string sp = spaced_operators(rest);
      auto tok = split(sp);
      const std::size_t want = in.op == Op::set ? 3 : in.op == Op::mat ? 5 : 5;
      if (tok.size() != want) return bad(fmt::format("{} expects {} operands, got {}", mne, want, tok.size()));
      auto v = var_of(tok[0]);
      if (!v) return std::unexpected(v.error());
      in.var = *v;
      if (in.op == Op::set || in.op == Op::mat) {
        if (tok[1] != "=") return bad(fmt::format("{} needs '='", mne));
        auto a = num_of(tok[2]);
        if (!a) return std::unexpected(a.error());
        in.n[0] = *a;
        if (in.op == Op::mat) {
          if (tok[3].size() != 1 || std::string_view("+-*/").find(tok[3][0]) == std::string_view::npos)
            return bad(fmt::format("MAT operator '{}' is not + - * /", tok[3]));
          in.mat_op = tok[3][0];
          auto b = num_of(tok[4]);
          if (!b) return std::unexpected(b.error());
          in.n[1] = *b;
        }
        return in;
      }
      auto c = cmp_of(tok[1]);
      if (!c) return std::unexpected(c.error());
      in.cmp = *c;
      for (std::size_t i = 2; i < 4; ++i) {
        auto x = num_of(tok[i]);
        if (!x) return std::unexpected(x.error());
        in.n[i - 2] = *x;
      }
      if (in.op == Op::cpj) {
        auto x = num_of(tok[4]);
        if (!x) return std::unexpected(x.error());
        in.n[2] = *x;
        if (auto r = check_num_ranges(in, {K::num, K::num, K::target}); !r) return std::unexpected(r.error());
      } else {
        auto b = parse_bit(tok[4]);
        if (!b) return std::unexpected(Fail{ClmError::command_io, fmt::format("'{}' is not an I/O bit", tok[4])});
        in.bit = *b;
      }
      return in;
    }
    default:
      break;
  }
  const auto lit = std::find_if(layouts().begin(), layouts().end(), [&](const Layout& l) { return l.op == in.op; });
  const auto tok = split(rest);
  std::size_t ti = 0, ni = 0;
  for (K k : lit->ops) {
    if (k == K::text) {
      if (ti >= tok.size()) return bad(fmt::format("{}: missing operand", mne));
      in.text = std::string(tok[ti++]);
      continue;
    }
    if (ti >= tok.size()) return bad(fmt::format("{}: missing operand {}", mne, ti + 1));
    const std::string_view t = tok[ti++];
    switch (k) {
      case K::bit:
      case K::bit2: {
        auto b = parse_bit(t);
        if (!b) return std::unexpected(Fail{ClmError::command_io, fmt::format("'{}' is not an I/O bit", t)});
        (k == K::bit ? in.bit : in.bit2) = *b;
        break;
      }
      case K::byte:
      case K::byte2: {
        auto b = parse_byte(t);
        if (!b) return std::unexpected(Fail{ClmError::command_io, fmt::format("'{}' is not an I/O byte", t)});
        (k == K::byte ? in.byte : in.byte2) = *b;
        break;
      }
      case K::pattern:
        if (t.size() != 8 || t.find_first_not_of("012") != std::string_view::npos)
          return bad(fmt::format("'{}' is not an 8-character pattern of 0/1/2", t));
        for (std::size_t i = 0; i < 8; ++i) in.pattern[i] = static_cast<std::uint8_t>(t[i] - '0');
        break;
      case K::var: {
        auto v = var_of(t);
        if (!v) return std::unexpected(v.error());
        in.var = *v;
        break;
      }
      case K::count: {
        // "+00000" adds, "000000" (sign character '0') sets the count to 0 (manual §5.7 COU)
        if (!t.empty() && t.front() == '0') {
          if (t.find_first_not_of('0') != std::string_view::npos)
            return bad(fmt::format("'{}' is not a count offset", t));
          in.counter_reset = true;
          in.n[ni++] = Num{};
          break;
        }
        auto x = num_of(t);
        if (!x || x->is_var() || x->value % micro_one != 0) return bad(fmt::format("'{}' is not a count offset", t));
        in.n[ni++] = *x;
        break;
      }
      default: {
        auto x = num_of(t);
        if (!x) return std::unexpected(x.error());
        in.n[ni++] = *x;
      }
    }
  }
  if (ti != tok.size()) return bad(fmt::format("{}: {} operand(s) too many", mne, tok.size() - ti));
  if (auto r = check_num_ranges(in, lit->ops); !r) return std::unexpected(r.error());
  if (in.op == Op::fak && !in.n[0].is_var() &&
      (in.n[0].value % micro_one != 0 || in.n[0].value < micro_one || in.n[0].value > 5 * micro_one))
    return std::unexpected(Fail{ClmError::axis_number, fmt::format("FAK axis {} is not 1..4 or 5 (master encoder 1)",
                                                                   to_double(in.n[0].value))});
  return in;
}

}  // namespace

std::string_view mnemonic(Op op) noexcept {
  return names[static_cast<std::size_t>(op)];
}

std::expected<Instruction, ProgramError> parse_instruction(std::string_view text) {
  auto r = parse(text);
  if (!r) return std::unexpected(ProgramError{r.error().error, -1, fmt::format("'{}': {}", text, r.error().why)});
  return std::move(*r);
}

std::string clear_counter_offset(std::string_view text) {
  auto tok = split(text);
  if (tok.size() < 3 || (tok[0] != "COU" && tok[0] != "BAC")) return std::string(text);
  const std::size_t idx = tok[0] == "COU" ? 1 : 2;
  const std::size_t pos = static_cast<std::size_t>(tok[idx].data() - text.data());
  const std::string repl = tok[0] == "COU" ? "+00000" : "+0000";
  std::string out(text);
  out.replace(pos, tok[idx].size(), repl);
  return out;
}

}  // namespace hil::controllers::clm14
