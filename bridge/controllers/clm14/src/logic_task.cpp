// SPDX-License-Identifier: MIT
#include "hil/controllers/clm14/logic_task.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <utility>

namespace hil::controllers::clm14 {

namespace {

struct Name {
  std::string_view text;
  LogicOp op;
};
constexpr std::array<Name, 25> op_names{{
    {"LD", LogicOp::ld},         {"LDN", LogicOp::ldn},         {"ST", LogicOp::st},       {"STN", LogicOp::stn},
    {"SET", LogicOp::set},       {"RES", LogicOp::res},         {"SETC", LogicOp::setc},   {"RESC", LogicOp::resc},
    {"SETCN", LogicOp::setcn},   {"RESCN", LogicOp::rescn},     {"AND", LogicOp::and_},    {"ANDN", LogicOp::andn},
    {"OR", LogicOp::or_},        {"ORN", LogicOp::orn},         {"XOR", LogicOp::xor_},    {"XORN", LogicOp::xorn},
    {"AND(", LogicOp::and_open}, {"ANDN(", LogicOp::andn_open}, {"OR(", LogicOp::or_open}, {"ORN(", LogicOp::orn_open},
    {"XOR(", LogicOp::xor_open}, {"XORN(", LogicOp::xorn_open}, {")", LogicOp::close},     {"NOP", LogicOp::nop},
    {"END", LogicOp::end},
}};

/// The store family st..rescn (contiguous in LogicOp): writes its operand, keeps the accumulator.
constexpr bool is_store(LogicOp op) {
  return op >= LogicOp::st && op <= LogicOp::rescn;
}
bool is_open(LogicOp op) {
  return op >= LogicOp::and_open && op <= LogicOp::xorn_open;
}

bool loadable(const BitAddress& a) {
  const int s = a.byte.source;
  switch (a.byte.area) {
    case Area::marker:
      return s == 0 || s == 1 || s == 4 || s == 5 || s == 6;
    case Area::input:
    case Area::output:
      return s <= 2;
  }
  return false;
}
bool storable(const BitAddress& a) {
  const int s = a.byte.source;
  if (a.byte.area == Area::marker) return s == 5 || s == 6;
  if (a.byte.area == Area::output) return s == 1 || (s == 2 && a.byte.byte >= 2 && a.byte.byte <= 5);
  return false;
}

/// Combine the accumulator with a value per the operator family (and/or/xor, negated or not).
bool combine(LogicOp family, bool acc, bool v) {
  switch (family) {
    case LogicOp::and_:
    case LogicOp::and_open:
      return acc && v;
    case LogicOp::andn:
    case LogicOp::andn_open:
      return acc && !v;
    case LogicOp::or_:
    case LogicOp::or_open:
      return acc || v;
    case LogicOp::orn:
    case LogicOp::orn_open:
      return acc || !v;
    case LogicOp::xor_:
    case LogicOp::xor_open:
      return acc != v;
    case LogicOp::xorn_open:
    case LogicOp::xorn:
      return acc == v;
    default:
      return v;
  }
}

/// The instruction's effect on (accumulator, operand bit): the manual's semantics, evaluated only
/// when compiling, to fill the truth tables that run() executes.
std::pair<bool, bool> effect(LogicOp op, bool acc, bool v) {
  switch (op) {
    case LogicOp::ld:
      return {v, v};
    case LogicOp::ldn:
      return {!v, v};
    case LogicOp::st:
      return {acc, acc};
    case LogicOp::stn:
      return {acc, !acc};
    case LogicOp::set:
      return {acc, true};
    case LogicOp::res:
      return {acc, false};
    case LogicOp::setc:
      return {acc, acc || v};
    case LogicOp::resc:
      return {acc, !acc && v};
    case LogicOp::setcn:
      return {acc, !acc || v};
    case LogicOp::rescn:
      return {acc, acc && v};
    default:
      return {combine(op, acc, v), v};
  }
}

LogicInstruction compiled(LogicOp op, const BitAddress& a) {
  LogicInstruction in{op, static_cast<std::uint8_t>(1U << a.bit), static_cast<std::uint16_t>(Image::offset(a.byte))};
  for (unsigned i = 0; i < 4; ++i) {
    const auto [acc, bit] = effect(op, (i & 2U) != 0, (i & 1U) != 0);
    in.acc_table = static_cast<std::uint8_t>(in.acc_table | (acc ? 1U << i : 0U));
    in.bit_table = static_cast<std::uint8_t>(in.bit_table | (bit ? 1U << i : 0U));
  }
  return in;
}

}  // namespace

std::expected<LogicProgram, ProgramError> LogicProgram::compile(const std::vector<std::string>& lines) {
  LogicProgram p;
  int depth = 0;
  const auto fail = [](int line, std::string why) {
    return std::unexpected(
        ProgramError{ClmError::logic_program, line, fmt::format("logic line {:04d}: {}", line, why)});
  };
  for (std::size_t n = 0; n < lines.size() && n < 1000; ++n) {
    const int line = static_cast<int>(n);
    std::string_view t = lines[n];
    while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
    while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
    if (t.empty()) t = "NOP";
    const auto sp = t.find(' ');
    const std::string_view word = t.substr(0, sp);
    std::string_view operand = sp == std::string_view::npos ? std::string_view{} : t.substr(sp + 1);
    while (!operand.empty() && operand.front() == ' ') operand.remove_prefix(1);
    // "AND (" is accepted for "AND(".
    std::string key(word);
    if (operand.starts_with("(") && operand.size() >= 1) {
      key += '(';
      operand.remove_prefix(1);
      while (!operand.empty() && operand.front() == ' ') operand.remove_prefix(1);
    }
    const auto it = std::find_if(op_names.begin(), op_names.end(), [&](const Name& nm) { return nm.text == key; });
    if (it == op_names.end()) return fail(line, fmt::format("'{}' is not a logic instruction", t));
    LogicInstruction in{it->op, 0, 0};
    const bool needs_operand =
        !(is_open(in.op) || in.op == LogicOp::close || in.op == LogicOp::nop || in.op == LogicOp::end);
    if (is_open(in.op) && !operand.empty()) {
      // "AND( M5.00.0" opens the bracket with its first operand loaded
      auto b = parse_bit(operand);
      if (!b || !loadable(*b)) return fail(line, fmt::format("operand '{}' cannot be read by the logic task", operand));
      p.code_.push_back(in);
      p.code_.push_back(compiled(LogicOp::ld, *b));
      if (++depth > 64) return fail(line, "more than 64 nested parentheses");
      continue;
    }
    if (needs_operand) {
      auto b = parse_bit(operand);
      if (!b) return fail(line, fmt::format("'{}' is not an operand I/Q/M x.yy.z", operand));
      if (is_store(in.op) ? !storable(*b) : !loadable(*b))
        return fail(line, fmt::format("operand {} is not allowed for {}", operand, key));
      in = compiled(in.op, *b);
      if (is_store(in.op) && b->byte.area == Area::output) {
        auto& m = p.owned_mask_[Image::offset(b->byte)];
        m = static_cast<std::uint8_t>(m | in.mask);
      }
    } else if (!operand.empty()) {
      return fail(line, fmt::format("{} takes no operand", key));
    }
    if (is_open(in.op)) ++depth;
    if (depth > 64) return fail(line, "more than 64 nested parentheses");
    if (in.op == LogicOp::close && --depth < 0) return fail(line, "')' without '('");
    if (in.op == LogicOp::end) {
      if (depth != 0) return fail(line, "unbalanced parentheses before END");
      return p;
    }
    if (in.op != LogicOp::nop) p.code_.push_back(in);
  }
  return fail(static_cast<int>(std::min<std::size_t>(lines.size(), 1000)) - 1, "the logic program has no END");
}

void LogicProgram::run(Image& image) const noexcept {
  auto& bytes = image.bytes();
  bool acc = false;
  // Bracket stack: the accumulator and the operator that waits for the bracketed result.
  std::array<std::pair<bool, LogicOp>, 64> stack{};
  std::size_t sp = 0;
  for (const auto& in : code_) {
    if (in.op >= LogicOp::and_open) [[unlikely]] {  // a bracket (NOP and END are never compiled)
      if (in.op == LogicOp::close) {
        if (sp > 0) {
          const auto [outer, op] = stack[--sp];
          acc = combine(op, outer, acc);
        }
      } else if (sp < stack.size()) {
        stack[sp++] = {acc, in.op};
      }
      continue;
    }
    auto& b = bytes[in.offset];
    const unsigned v = (b & in.mask) != 0 ? 1U : 0U;
    const bool acc0 = ((in.acc_table >> v) & 1U) != 0;
    const bool acc1 = ((in.acc_table >> (2U + v)) & 1U) != 0;
    if (is_store(in.op)) {
      const bool bit = ((in.bit_table >> ((acc ? 2U : 0U) + v)) & 1U) != 0;
      b = static_cast<std::uint8_t>((b & ~in.mask) | (bit ? in.mask : 0U));
    }
    acc = acc ? acc1 : acc0;
  }
}

}  // namespace hil::controllers::clm14
