// SPDX-License-Identifier: MIT
// WF 725/726 automatic buffer (docs/wf725.md, "Automatic buffer"): buffers 1-6, two per axis
// (A: 1/2, B: 3/4, C: 5/6), at most 50 blocks each; the PLC sets a buffer's length (data code 48)
// and reloads its blocks 1..length ascending without gaps from a user data block (data code 49)
// while the other buffer of the pair runs; M12 in an odd buffer changes to the even one, M11 in an
// even buffer back to the odd one (digest §5.2 B2/B3 [INF]). Errors: B0, B1, B2, B3 (traversing),
// 143, 144, 146, 147, 151, 152, 155 (program I/O), 203 (memory administration).
#include <fmt/format.h>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

using namespace wf_db;

bool has_m(const Wf725Program& p, int m) noexcept {
  for (const auto& b : p.blocks)
    if (b.m && *b.m == m) return true;
  return false;
}

}  // namespace

bool Wf725Controller::own_buffer(int buffer) const noexcept {
  const int first = 2 * (opt_.axis - 'A') + 1;
  return buffer == first || buffer == first + 1;
}

void Wf725Controller::buffer_length(int buffer, int length, TimePoint now) {
  if (buffer == 0) return raise_io(155, now);
  if (buffer < 0 || buffer > 6 || !own_buffer(buffer))
    return raise_io(151, now,
                    fmt::format("buffer {} (axis {}: {}, {})", buffer, opt_.axis, 2 * (opt_.axis - 'A') + 1,
                                2 * (opt_.axis - 'A') + 2));
  if (length > wf725_buffer_blocks) return raise_io(152, now, fmt::format("{} blocks", length));
  if (length <= 0) return raise_io(143, now, fmt::format("buffer length {}", length));
  if (running_buffer_ == buffer) return raise_io(203, now, fmt::format("buffer {} runs", buffer), "memory_admin");
  auto& b = buffers_[static_cast<std::size_t>(buffer - 1)];
  b.program = Wf725Program{};
  b.program.number = buffer;
  b.program.ram = true;
  b.length = length;
}

void Wf725Controller::buffer_reload(int buffer, int db, TimePoint now) {
  if (buffer <= 0 || buffer > 6 || !own_buffer(buffer)) return raise_io(151, now, fmt::format("buffer {}", buffer));
  if (running_buffer_ == buffer) return raise_io(203, now, fmt::format("buffer {} runs", buffer), "memory_admin");
  auto& buf = buffers_[static_cast<std::size_t>(buffer - 1)];
  if (buf.length == 0) return raise_io(143, now, fmt::format("buffer {}: set its length first (data code 48)", buffer));
  const auto it = db >= 1 && db <= 255 ? user_blocks_->find(static_cast<std::uint8_t>(db)) : user_blocks_->end();
  if (it == user_blocks_->end() || it->second.empty() || it->second[0] == 0 ||
      it->second[0] > 2 * (it->second.size() - 1))
    return raise_io(401, now, fmt::format("user DB{} holds no block text", db), "schale");
  std::string text = fmt::format("%{}\n", buffer);
  for (std::size_t i = 0; i < it->second[0]; ++i) {
    const std::uint16_t w = it->second[1 + i / 2];
    text.push_back(static_cast<char>(i % 2 == 0 ? w >> 8 : w & 0xFF));
  }
  auto parsed = parse_wf725_programs(text, syntax_);
  if (!parsed) {
    const auto& e = parsed.error();
    return raise_io(e.code, now, fmt::format("DB{} N{}: {}", db, e.block, e.message),
                    e.code < 200 ? "program_io" : "memory_admin");
  }
  if (parsed->size() != 1)
    return raise_io(220, now, fmt::format("DB{}: blocks only, no program header", db), "memory_admin");
  const auto& blocks = parsed->front().blocks;
  // All or nothing: every check before the first block is taken.
  std::size_t loaded = buf.program.blocks.size();
  for (const auto& b : blocks) {
    if (b.number < 1 || b.number > wf725_buffer_blocks) return raise_io(147, now, fmt::format("N{}", b.number));
    if (b.number != static_cast<int>(loaded) + 1)
      return raise_io(144, now, fmt::format("N{} where N{} is due", b.number, loaded + 1));
    const bool any_g = b.group(1) >= 0 || b.group(2) >= 0 || b.group(3) >= 0 || b.group(4) >= 0;
    if (!any_g && !b.x && !b.f && !b.m && !b.tool && !b.call) return raise_io(146, now, fmt::format("N{}", b.number));
    if (static_cast<int>(++loaded) > buf.length)
      return raise_io(143, now, fmt::format("N{} beyond the buffer length {}", b.number, buf.length));
  }
  buf.program.blocks.insert(buf.program.blocks.end(), blocks.begin(), blocks.end());
}

bool Wf725Controller::enter_buffer(int n, TimePoint now) {
  const auto& buf = buffers_[static_cast<std::size_t>(n - 1)];
  if (!buf.complete()) return raise_wf(0xB1, now, fmt::format("buffer {}", n)), false;
  if (n % 2 == 1 && has_m(buf.program, 11)) return raise_wf(0xB2, now, fmt::format("buffer {}", n)), false;
  if (n % 2 == 0 && has_m(buf.program, 12)) return raise_wf(0xB3, now, fmt::format("buffer {}", n)), false;
  stack_.assign(1, Frame{&buf.program, 0, 1});
  running_buffer_ = n;
  running_program_ = n;
  step_ = Step::fetch;
  return true;
}

bool Wf725Controller::start_buffer(TimePoint now) {
  const int n = db_.read_word(dw_program);
  if (n < 1 || n > 6 || !own_buffer(n))
    return raise_wf(0xB0, now, fmt::format("buffer {} (axis {})", n, opt_.axis)), false;
  single_ = false;
  absolute_ = true;
  feed_ = 0;
  target_mm_ = machine_command_mm();
  after_m_ = -1;
  m0_pending_ = false;
  if (!enter_buffer(n, now)) return false;
  job_ = Job::program;
  return true;
}

bool Wf725Controller::buffer_change(TimePoint now) {
  const Wf725Block* b = current_block();
  if (b == nullptr || !b->m || (*b->m != 11 && *b->m != 12) || stack_.size() != 1) return false;
  const int from = running_buffer_;
  const int to = *b->m == 12 ? from + 1 : from - 1;                     // M12: odd -> even, M11: even -> odd
  buffers_[static_cast<std::size_t>(from - 1)].program.blocks.clear();  // consumed
  running_buffer_ = 0;
  if (!enter_buffer(to, now)) {
    abort_job();
    return true;
  }
  return true;
}

}  // namespace hil::controllers::s5
