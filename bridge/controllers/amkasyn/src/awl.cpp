// SPDX-License-Identifier: MIT
// The APSF statement-list subset: parser and step-bounded interpreter. See awl.hpp.
#include "hil/controllers/amkasyn/awl.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "text_trim.hpp"

namespace hil::controllers::amkasyn {
namespace {

using Op = AwlInstruction::Op;

std::string upper(std::string_view s) {
  std::string r(s);
  for (auto& c : r) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return r;
}

using detail::trim;

bool number(std::string_view s, long long& v, int base = 10) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, base);
  return r.ec == std::errc{} && r.ptr == s.data() + s.size() && !s.empty();
}

// "EB 12", "MW 4", "DD 6", "E 216.0", "KF -5", "KH 00FF", "KM 0000 1111", "KD 30000", "=LBL".
struct Operand {
  AwlArea area = AwlArea::none;
  int width = 0, address = 0, bit = 0;
  std::int32_t constant = 0;
  std::string label;
  std::string block;  ///< FB / PB / OB / SB / DB / T of a block or timer operand
};

std::expected<Operand, std::string> parse_operand(std::string_view text) {
  Operand o;
  std::string t = upper(trim(text));
  if (t.empty()) return o;
  if (t.front() == '=') {
    o.label = std::string(trim(std::string_view(t).substr(1)));
    if (o.label.empty()) return std::unexpected("a jump needs a label after '='");
    return o;
  }
  const auto sp = t.find_first_of(" \t0123456789-+");
  const std::string key = t.substr(0, sp);
  const std::string_view rest = sp == std::string::npos ? std::string_view{} : trim(std::string_view(t).substr(sp));
  long long v = 0;
  if (key == "KF" || key == "KB" || key == "KD") {
    if (!number(rest, v)) return std::unexpected(fmt::format("'{}': not a number", rest));
    const long long lo = key == "KF" ? -32768 : key == "KB" ? 0 : std::numeric_limits<std::int32_t>::min();
    const long long hi = key == "KF" ? 32767 : key == "KB" ? 255 : std::numeric_limits<std::int32_t>::max();
    if (v < lo || v > hi) return std::unexpected(fmt::format("{} {} is outside {}..{}", key, v, lo, hi));
    o.area = AwlArea::constant;
    o.width = key == "KB" ? 8 : key == "KF" ? 16 : 32;
    o.constant = static_cast<std::int32_t>(key == "KF" ? static_cast<std::uint16_t>(v) : v);
    return o;
  }
  if (key == "KH" || key == "KM") {
    std::string digits;
    for (char c : rest)
      if (!std::isspace(static_cast<unsigned char>(c))) digits += c;
    if (!number(digits, v, key == "KH" ? 16 : 2) || v < 0 || v > 0xFFFF)
      return std::unexpected(fmt::format("{} {}: 16 bits in {}", key, rest, key == "KH" ? "hex" : "binary"));
    o.area = AwlArea::constant;
    o.width = 16;
    o.constant = static_cast<std::int32_t>(v);
    return o;
  }
  if (key == "FB" || key == "PB" || key == "OB" || key == "SB" || key == "DB" || key == "T") {
    if (!number(rest, v) || v < 0 || v > 255) return std::unexpected(fmt::format("{} {}: a block number", key, rest));
    o.block = key;
    o.address = static_cast<int>(v);
    return o;
  }
  static const std::map<std::string, std::pair<AwlArea, int>> areas = {
      {"EB", {AwlArea::e, 8}},  {"EW", {AwlArea::e, 16}},  {"ED", {AwlArea::e, 32}},  {"AB", {AwlArea::a, 8}},
      {"AW", {AwlArea::a, 16}}, {"AD", {AwlArea::a, 32}},  {"MB", {AwlArea::m, 8}},   {"MW", {AwlArea::m, 16}},
      {"MD", {AwlArea::m, 32}}, {"DW", {AwlArea::db, 16}}, {"DD", {AwlArea::db, 32}}, {"E", {AwlArea::e, 1}},
      {"A", {AwlArea::a, 1}},   {"M", {AwlArea::m, 1}}};
  const auto it = areas.find(key);
  if (it == areas.end()) return std::unexpected(fmt::format("'{}' is not an operand of the subset", text));
  o.area = it->second.first;
  o.width = it->second.second;
  if (o.width == 1) {
    const auto dot = rest.find('.');
    long long b = 0;
    if (dot == std::string_view::npos || !number(rest.substr(0, dot), v) || !number(rest.substr(dot + 1), b) || v < 0 ||
        v > 255 || b < 0 || b > 7)
      return std::unexpected(fmt::format("'{}': a bit operand is byte 0..255 '.' bit 0..7", text));
    o.address = static_cast<int>(v);
    o.bit = static_cast<int>(b);
    return o;
  }
  if (!number(rest, v) || v < 0) return std::unexpected(fmt::format("'{}': an address", text));
  const long long max = o.area == AwlArea::db ? 2047 : 256 - o.width / 8;
  if (v > max) return std::unexpected(fmt::format("'{}': the address must be 0..{}", text, max));
  o.address = static_cast<int>(v);
  return o;
}

std::int32_t sext16(std::int32_t v) noexcept {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(v));
}
std::int32_t wrap32(std::int64_t v) noexcept {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)));
}

}  // namespace

std::expected<AwlProgram, std::string> parse_awl(std::string_view text) {
  AwlProgram p;
  std::map<std::string, int> labels;
  std::vector<std::pair<std::size_t, std::string>> jumps;  // instruction, label
  std::istringstream in{std::string(text)};
  std::string raw;
  int line_no = 0;
  auto bad = [&](std::string_view stmt, const std::string& why) {
    return std::unexpected(fmt::format("FB line {}: '{}': {}", line_no, trim(stmt), why));
  };
  while (std::getline(in, raw)) {
    ++line_no;
    std::string_view line = raw;
    for (const char* c : {";", "//"})
      if (const auto k = line.find(c); k != std::string_view::npos) line = line.substr(0, k);
    line = trim(line);
    if (line.empty()) continue;
    const std::string up = upper(line);
    if (up.rfind("NAME", 0) == 0 || up.rfind("BIB", 0) == 0 ||
        (up.rfind("FB", 0) == 0 && p.code.empty() && labels.empty()))
      continue;  // header lines of the listing
    if (const auto colon = line.find(':'); colon != std::string_view::npos && colon > 0 && colon <= 8 &&
                                           line.substr(0, colon).find_first_of(" \t") == std::string_view::npos &&
                                           line.front() != ':') {
      const std::string label = upper(line.substr(0, colon));
      if (labels.contains(label)) return bad(line, "the label is defined twice");
      labels[label] = static_cast<int>(p.code.size());
      line = trim(line.substr(colon + 1));
      if (line.empty()) continue;
    }
    const auto sp = line.find_first_of(" \t");
    const std::string mn = upper(line.substr(0, sp));
    const std::string_view operand_text = sp == std::string_view::npos ? std::string_view{} : line.substr(sp);
    static const std::map<std::string, std::pair<Op, int>> shifts = {
        {"SLW", {Op::shl_w, 15}}, {"SRW", {Op::shr_w, 15}}, {"SLD", {Op::shl_d, 32}}, {"SRD", {Op::shr_d, 32}}};
    if (const auto sh = shifts.find(mn); sh != shifts.end()) {
      long long n = 0;
      if (!number(operand_text, n) || n < 0 || n > sh->second.second)
        return bad(line, fmt::format("{} takes a shift count 0..{}", mn, sh->second.second));
      AwlInstruction shift;
      shift.op = sh->second.first;
      shift.address = static_cast<int>(n);
      shift.line = line_no;
      shift.text = std::string(line);
      p.code.push_back(std::move(shift));
      continue;
    }
    auto operand = parse_operand(operand_text);
    if (!operand) return bad(line, operand.error());
    AwlInstruction ins;
    ins.line = line_no;
    ins.text = std::string(line);
    ins.area = operand->area;
    ins.width = operand->width;
    ins.address = operand->address;
    ins.bit = operand->bit;
    ins.constant = operand->constant;
    auto forbid = [&] {
      ins.op = Op::forbidden;
      p.forbidden.push_back(fmt::format("line {}: {}", line_no, ins.text));
    };
    static const std::map<std::string, Op> plain = {
        {"+F", Op::add_f},     {"-F", Op::sub_f},      {"XF", Op::mul_f},          {":F", Op::div_f}, {"+D", Op::add_d},
        {"-D", Op::sub_d},     {"XD", Op::mul_d},      {":D", Op::div_d},          {"WWD", Op::wwd},  {"TAK", Op::tak},
        {"BE", Op::block_end}, {"BEA", Op::block_end}, {"BEB", Op::block_end_rlo}, {"UW", Op::and_w}, {"OW", Op::or_w},
        {"XOW", Op::xor_w},    {"KEW", Op::not_w},     {"KZW", Op::neg_w}};
    static const std::map<std::string, std::pair<Op, int>> compares = {
        {"!=F", {Op::cmp_f, 0}}, {"><F", {Op::cmp_f, 1}}, {">F", {Op::cmp_f, 2}},  {">=F", {Op::cmp_f, 3}},
        {"<F", {Op::cmp_f, 4}},  {"<=F", {Op::cmp_f, 5}}, {"!=D", {Op::cmp_d, 0}}, {"><D", {Op::cmp_d, 1}},
        {">D", {Op::cmp_d, 2}},  {">=D", {Op::cmp_d, 3}}, {"<D", {Op::cmp_d, 4}},  {"<=D", {Op::cmp_d, 5}}};
    static const std::map<std::string, Op> bits = {{"U", Op::and_bit}, {"UN", Op::and_not}, {"O", Op::or_bit},
                                                   {"ON", Op::or_not}, {"=", Op::assign},   {"S", Op::set},
                                                   {"R", Op::reset}};
    static const std::map<std::string, Op> jump_ops = {
        {"SPA", Op::jump},          {"SPB", Op::jump_rlo}, {"SPBN", Op::jump_not_rlo}, {"SPZ", Op::jump_zero},
        {"SPN", Op::jump_not_zero}, {"SPP", Op::jump_pos}, {"SPM", Op::jump_neg}};
    const bool has_operand = !trim(operand_text).empty();
    if (mn == "SI" || mn == "SV" || mn == "SE" || mn == "SS" || mn == "SA" || mn == "STP" || mn == "STS" ||
        (mn == "R" && operand->block == "T") || (mn == "E" && operand->block == "DB") ||
        ((mn == "SPA" || mn == "SPB") && !operand->block.empty() && operand->block != "T")) {
      forbid();
    } else if (mn == "L" || mn == "T") {
      if (!has_operand || !operand->block.empty() || !operand->label.empty() || operand->width == 1 ||
          (mn == "T" && operand->area == AwlArea::constant))
        return bad(line, mn == "L" ? "L needs a byte/word/double-word operand or a constant"
                                   : "T needs a byte/word/double-word operand");
      ins.op = mn == "L" ? Op::load : Op::transfer;
    } else if (const auto pl = plain.find(mn); pl != plain.end()) {
      if (has_operand) return bad(line, "this statement takes no operand");
      ins.op = pl->second;
    } else if (mn == "ADD") {
      if (operand->area != AwlArea::constant || operand->width != 16) return bad(line, "ADD takes KF n");
      ins.op = Op::add_k;
      ins.constant = sext16(operand->constant);
    } else if (const auto c = compares.find(mn); c != compares.end()) {
      if (has_operand) return bad(line, "a comparison takes no operand");
      ins.op = c->second.first;
      ins.constant = c->second.second;
    } else if (const auto b = bits.find(mn); b != bits.end()) {
      if (operand->width != 1) return bad(line, "a bit operation needs E/A/M byte.bit");
      if ((b->second == Op::assign || b->second == Op::set || b->second == Op::reset) && operand->area == AwlArea::e)
        return bad(line, "=, S and R write A or M bits");
      ins.op = b->second;
    } else if (const auto j = jump_ops.find(mn); j != jump_ops.end()) {
      if (operand->label.empty()) return bad(line, "a jump needs '=label'");
      ins.op = j->second;
      jumps.emplace_back(p.code.size(), operand->label);
    } else if (mn == "A" && operand->block == "DB") {
      ins.op = Op::open_db;
    } else {
      return bad(line, fmt::format("'{}' is not a statement of the APSF subset (docs/amkasyn.md)", mn));
    }
    p.code.push_back(std::move(ins));
  }
  for (const auto& [at, label] : jumps) {
    const auto it = labels.find(label);
    if (it == labels.end())
      return std::unexpected(
          fmt::format("FB line {}: '{}': label {} is not defined", p.code[at].line, p.code[at].text, label));
    p.code[at].address = it->second;
  }
  return p;
}

AwlRun run_awl(const AwlProgram& program, AwlMemory& mem, int open_db, int budget) noexcept {
  AwlRun r;
  std::int32_t accu1 = 0, accu2 = 0;
  bool rlo = false, first = true;
  int db = open_db;
  std::size_t pc = 0;
  auto fail = [&](const AwlInstruction& ins, const char* why) {
    r.ok = false;
    try {
      r.error = fmt::format("FB line {}: '{}': {}", ins.line, ins.text, why);
    } catch (...) {
      r.error.clear();
    }
    return r;
  };
  while (pc < program.code.size()) {
    if (++r.steps > budget) {
      r.ok = false;
      try {
        r.error = fmt::format("the FB ran more than {} statements in one SF cycle (an endless loop?)", budget);
      } catch (...) {
      }
      return r;
    }
    const AwlInstruction& ins = program.code[pc++];
    auto read = [&](std::int32_t& v) -> bool {
      if (ins.area == AwlArea::constant) {
        v = ins.constant;
        return true;
      }
      if (ins.area == AwlArea::db) {
        std::uint16_t w0 = 0, w1 = 0;
        if (!mem.db_word(db, ins.address, w0)) return false;
        if (ins.width == 32 && !mem.db_word(db, ins.address + 1, w1)) return false;
        v = static_cast<std::int32_t>((static_cast<std::uint32_t>(w1) << 16) | w0);  // DD: low word first
        return true;
      }
      std::uint32_t u = 0;
      for (int k = 0; k < ins.width / 8; ++k) u = (u << 8) | mem.byte(ins.area, ins.address + k);  // S5 order
      v = static_cast<std::int32_t>(u);
      return true;
    };
    auto write = [&](std::int32_t v) -> bool {
      const auto u = static_cast<std::uint32_t>(v);
      if (ins.area == AwlArea::db) {
        if (!mem.set_db_word(db, ins.address, static_cast<std::uint16_t>(u & 0xFFFF))) return false;
        return ins.width != 32 || mem.set_db_word(db, ins.address + 1, static_cast<std::uint16_t>(u >> 16));
      }
      const int n = ins.width / 8;
      for (int k = 0; k < n; ++k)
        mem.set_byte(ins.area, ins.address + k, static_cast<std::uint8_t>(u >> (8 * (n - 1 - k))));
      return true;
    };
    auto bit = [&] { return ((mem.byte(ins.area, ins.address) >> ins.bit) & 1) != 0; };
    auto set_bit = [&](bool v) {
      const auto b = mem.byte(ins.area, ins.address);
      const auto m = static_cast<std::uint8_t>(1u << ins.bit);
      mem.set_byte(ins.area, ins.address, v ? static_cast<std::uint8_t>(b | m) : static_cast<std::uint8_t>(b & ~m));
    };
    auto compare = [&](std::int64_t a, std::int64_t b) {
      switch (ins.constant) {
        case 0:
          return a == b;
        case 1:
          return a != b;
        case 2:
          return a > b;
        case 3:
          return a >= b;
        case 4:
          return a < b;
        default:
          return a <= b;
      }
    };
    const std::int32_t a16 = sext16(accu2), b16 = sext16(accu1);
    switch (ins.op) {
      case Op::load: {
        std::int32_t v = 0;
        if (!read(v)) return fail(ins, db ? "the data word is beyond the open DB" : "no DB is open (A DB n)");
        accu2 = accu1;
        accu1 = v;
        break;
      }
      case Op::transfer:
        if (!write(accu1)) return fail(ins, db ? "the data word is beyond the open DB" : "no DB is open (A DB n)");
        break;
      case Op::add_f:
        accu1 = sext16(a16 + b16);
        break;
      case Op::sub_f:
        accu1 = sext16(a16 - b16);
        break;
      case Op::mul_f:
        accu1 = sext16(a16 * b16);
        break;
      case Op::div_f:
        accu1 = b16 == 0 ? 0 : sext16(a16 / b16);
        break;
      case Op::add_d:
        accu1 = wrap32(static_cast<std::int64_t>(accu2) + accu1);
        break;
      case Op::sub_d:
        accu1 = wrap32(static_cast<std::int64_t>(accu2) - accu1);
        break;
      case Op::mul_d:
        accu1 = wrap32(static_cast<std::int64_t>(accu2) * accu1);
        break;
      case Op::div_d:
        accu1 = accu1 == 0 ? 0 : wrap32(static_cast<std::int64_t>(accu2) / accu1);
        break;
      case Op::wwd:
        accu1 = sext16(accu1);
        break;
      case Op::and_w:
        accu1 = (accu2 & accu1) & 0xFFFF;
        break;
      case Op::or_w:
        accu1 = (accu2 | accu1) & 0xFFFF;
        break;
      case Op::xor_w:
        accu1 = (accu2 ^ accu1) & 0xFFFF;
        break;
      case Op::not_w:
        accu1 = ~accu1 & 0xFFFF;
        break;
      case Op::neg_w:
        accu1 = sext16(-b16);
        break;
      case Op::shl_w:
        accu1 = static_cast<std::int32_t>((static_cast<std::uint32_t>(accu1) << ins.address) & 0xFFFFu);
        break;
      case Op::shr_w:
        accu1 = static_cast<std::int32_t>((static_cast<std::uint32_t>(accu1) & 0xFFFFu) >> ins.address);
        break;
      case Op::shl_d:
        accu1 = ins.address >= 32 ? 0 : static_cast<std::int32_t>(static_cast<std::uint32_t>(accu1) << ins.address);
        break;
      case Op::shr_d:
        accu1 = ins.address >= 32 ? 0 : static_cast<std::int32_t>(static_cast<std::uint32_t>(accu1) >> ins.address);
        break;
      case Op::tak:
        std::swap(accu1, accu2);
        break;
      case Op::add_k:
        accu1 = wrap32(static_cast<std::int64_t>(accu1) + ins.constant);
        break;
      case Op::cmp_f:
        rlo = compare(a16, b16);
        first = false;
        break;
      case Op::cmp_d:
        rlo = compare(accu2, accu1);
        first = false;
        break;
      case Op::and_bit:
      case Op::and_not:
      case Op::or_bit:
      case Op::or_not: {
        const bool v = (ins.op == Op::and_not || ins.op == Op::or_not) ? !bit() : bit();
        if (first)
          rlo = v;
        else
          rlo = (ins.op == Op::and_bit || ins.op == Op::and_not) ? (rlo && v) : (rlo || v);
        first = false;
        break;
      }
      case Op::assign:
        set_bit(rlo);
        first = true;
        break;
      case Op::set:
        if (rlo) set_bit(true);
        first = true;
        break;
      case Op::reset:
        if (rlo) set_bit(false);
        first = true;
        break;
      case Op::jump:
        pc = static_cast<std::size_t>(ins.address);
        break;
      case Op::jump_rlo:
        if (rlo) pc = static_cast<std::size_t>(ins.address);
        first = true;
        rlo = true;
        break;
      case Op::jump_not_rlo:
        if (!rlo) pc = static_cast<std::size_t>(ins.address);
        first = true;
        rlo = true;
        break;
      case Op::jump_zero:
        if (accu1 == 0) pc = static_cast<std::size_t>(ins.address);
        break;
      case Op::jump_not_zero:
        if (accu1 != 0) pc = static_cast<std::size_t>(ins.address);
        break;
      case Op::jump_pos:
        if (accu1 > 0) pc = static_cast<std::size_t>(ins.address);
        break;
      case Op::jump_neg:
        if (accu1 < 0) pc = static_cast<std::size_t>(ins.address);
        break;
      case Op::block_end:
        return r;
      case Op::block_end_rlo:
        if (rlo) return r;
        first = true;
        rlo = true;
        break;
      case Op::open_db:
        db = ins.address;
        break;
      case Op::forbidden:
        return fail(ins, "a forbidden command in an APSF (running time error)");
    }
  }
  return r;
}

}  // namespace hil::controllers::amkasyn
