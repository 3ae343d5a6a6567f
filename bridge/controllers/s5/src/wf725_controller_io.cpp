// SPDX-License-Identifier: MIT
// WF 725/726 program and machine-data input/output (docs/wf725.md, "Program input/output"): the
// user data blocks beside the module, data codes 44/45 (what the S5 "Software Schale" FB does:
// copy a program between a user DB and the module, errors 401/402), the MD as stored integers
// (data codes 50/51 and the MD image of `hilbridge emulate wf725`).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

/// MD 3 and MD 22 are stored in 0.01 steps (10^-2 mm/min, 10^-2 (m/min)/mm), every other MD as is.
long double md_lsb(int n) noexcept {
  return (n == 3 || n == 22) ? 0.01L : 1.0L;
}

}  // namespace

std::expected<std::uint16_t, std::string> Wf725Controller::read_data_word(int db, int dw) const {
  if (db == opt_.db) return Controller::read_data_word(db, dw);
  const auto it = user_blocks_->find(static_cast<std::uint8_t>(std::clamp(db, 0, 255)));
  if (db < 1 || db > 255 || it == user_blocks_->end())
    return std::unexpected(
        fmt::format("DB{} does not exist: the WF's DB axis is DB{}, user data blocks are "
                    "created by their first write",
                    db, opt_.db));
  if (dw < 0 || static_cast<std::size_t>(dw) >= it->second.size())
    return std::unexpected(fmt::format("DB{} has DW 0..{}: DW {} is beyond it", db, it->second.size() - 1, dw));
  return it->second[static_cast<std::size_t>(dw)];
}

std::expected<void, std::string> Wf725Controller::write_data_word(int db, int dw, std::uint16_t value) {
  if (db == opt_.db) return Controller::write_data_word(db, dw, value);
  if (db < 1 || db > 255) return std::unexpected(fmt::format("DB{}: DB numbers are 1..255", db));
  if (dw < 0 || static_cast<std::size_t>(dw) >= wf725_user_block_words)
    return std::unexpected(
        fmt::format("DB{} DW {}: a user data block has DW 0..{}", db, dw, wf725_user_block_words - 1));
  auto& words = (*user_blocks_)[static_cast<std::uint8_t>(db)];
  if (words.size() <= static_cast<std::size_t>(dw)) words.resize(static_cast<std::size_t>(dw) + 1, 0);
  words[static_cast<std::size_t>(dw)] = value;
  return {};
}

std::int32_t Wf725Controller::read_machine_data(int n) const noexcept {
  if (n < 1 || n > 50) return 0;
  return static_cast<std::int32_t>(std::llround(static_cast<double>(md_.get(n) / md_lsb(n))));
}

int Wf725Controller::write_machine_data(int n, std::int32_t stored) noexcept {
  if (n < 1 || n > 50) return 121;
  if (!machine_data_mode()) return 201;
  const long double v = static_cast<long double>(stored) * md_lsb(n);
  if (wf725_md_shapes_axis(n) && v != md_.get(n) &&
      std::find(pending_md_.begin(), pending_md_.end(), n) == pending_md_.end())
    pending_md_.push_back(n);
  md_.set(n, v);
  return 0;
}

// A program in a user data block (our layout, docs/wf725.md): DW 0 = number of characters, DW 1..
// the program text (the file format of wf725_program.hpp), two characters per word, high byte first.
void Wf725Controller::program_input(int db, TimePoint now) {
  const auto it = db >= 1 && db <= 255 ? user_blocks_->find(static_cast<std::uint8_t>(db)) : user_blocks_->end();
  if (it == user_blocks_->end() || it->second.empty() || it->second[0] == 0)
    return raise_io(401, now, fmt::format("user DB{} holds no program text", db), "schale");
  const auto& w = it->second;
  const std::size_t chars = w[0];
  if (chars > 2 * (w.size() - 1))
    return raise_io(401, now,
                    fmt::format("DB{}: DW 0 gives {} characters, the block holds {}", db, chars, 2 * (w.size() - 1)),
                    "schale");
  std::string text;
  text.reserve(chars);
  for (std::size_t i = 0; i < chars; ++i) {
    const std::uint16_t word = w[1 + i / 2];
    text.push_back(static_cast<char>(i % 2 == 0 ? word >> 8 : word & 0xFF));
  }
  auto progs = parse_wf725_programs(text, syntax_);
  if (!progs) {
    const auto& e = progs.error();
    return raise_io(e.code, now,
                    fmt::format("DB{} line {}, program {} N{}: {}", db, e.line, e.program, e.block, e.message),
                    e.code < 200 ? "program_io" : "memory_admin");
  }
  // All or nothing: a program the memory refuses leaves the memory as it was.
  // The trial is a copy; the memory itself is changed in place (an axis of the module may run
  // another of its programs: stored programs never move).
  Wf725ProgramStore trial = *store_;
  for (const auto& p : *progs) {
    if (running_program_ != 0 && p.number == running_program_)
      return raise_io(105, now, fmt::format("program {} runs", p.number));
    if (const int e = trial.store(p)) return raise_io(e, now, fmt::format("program {}", p.number));
  }
  for (auto& p : *progs) (void)store_->store(std::move(p));
}

void Wf725Controller::program_output(int program, int db, TimePoint now) {
  if (program == 0) return raise_io(125, now);
  const Wf725Program* p = store_->find(program);
  if (p == nullptr) return raise_io(127, now, fmt::format("program {}", program));
  if (db < 1 || db > 255 || db == opt_.db)
    return raise_io(402, now, fmt::format("DB{} is not a user data block", db), "schale");
  const std::string text = make_wf725_program_text(*p);
  if (1 + (text.size() + 1) / 2 > wf725_user_block_words)
    return raise_io(402, now,
                    fmt::format("program {} has {} characters, a user DB holds {}", program, text.size(),
                                2 * (wf725_user_block_words - 1)),
                    "schale");
  std::vector<std::uint16_t> words(1 + (text.size() + 1) / 2, 0);
  words[0] = static_cast<std::uint16_t>(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<std::uint8_t>(text[i]);
    words[1 + i / 2] |= static_cast<std::uint16_t>(i % 2 == 0 ? c << 8 : c);
  }
  (*user_blocks_)[static_cast<std::uint8_t>(db)] = std::move(words);
}

}  // namespace hil::controllers::s5
