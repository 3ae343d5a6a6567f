// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/wf725_program_store.hpp"

#include <algorithm>

namespace hil::controllers::s5 {

int Wf725ProgramStore::blocks_used(bool ram) const noexcept {
  int n = 0;
  for (const auto& p : programs_)
    if (p.ram == ram) n += static_cast<int>(p.blocks.size());
  return n;
}

const Wf725Program* Wf725ProgramStore::find(int number) const noexcept {
  for (const auto& p : programs_)
    if (p.number == number) return &p;
  return nullptr;
}

int Wf725ProgramStore::store(Wf725Program p) {
  if (p.number == 0) return 125;
  if (in_use(p.number)) return 105;
  const auto it = std::find_if(programs_.begin(), programs_.end(), [&](const auto& q) { return q.number == p.number; });
  if (it == programs_.end() && static_cast<int>(programs_.size()) >= limits_.programs) return 124;
  int used = blocks_used(p.ram);
  if (it != programs_.end() && it->ram == p.ram) used -= static_cast<int>(it->blocks.size());
  const int capacity = p.ram ? limits_.ram_blocks : limits_.eeprom_blocks;
  if (used + static_cast<int>(p.blocks.size()) > capacity) return 123;
  if (it != programs_.end()) {
    *it = std::move(p);
  } else {
    programs_.push_back(std::move(p));
  }
  ++revision_;
  return 0;
}

int Wf725ProgramStore::remove(int number) {
  if (number == 0) return 125;
  const auto it = std::find_if(programs_.begin(), programs_.end(), [&](const auto& q) { return q.number == number; });
  if (it == programs_.end()) return 127;
  if (in_use(number)) return 105;
  programs_.erase(it);
  ++revision_;
  return 0;
}

int Wf725ProgramStore::remove_block(int program, int block) {
  if (program == 0) return 125;
  if (block == 0) return 126;
  const auto it = std::find_if(programs_.begin(), programs_.end(), [&](const auto& q) { return q.number == program; });
  if (it == programs_.end()) return 127;
  const auto b = std::find_if(it->blocks.begin(), it->blocks.end(), [&](const auto& x) { return x.number == block; });
  if (b == it->blocks.end()) return 128;
  if (in_use(program)) return 105;  // an axis of the module runs it: its blocks must not move
  it->blocks.erase(b);
  ++revision_;
  return 0;
}

std::vector<int> Wf725ProgramStore::numbers() const {
  std::vector<int> n;
  for (const auto& p : programs_) n.push_back(p.number);
  std::sort(n.begin(), n.end());
  return n;
}

int Wf725ProgramStore::teach(int program, int block_number, Wf725Block block, bool ram) {
  if (program == 0) return 135;
  if (block_number == 0) return 136;
  if (in_use(program)) return 105;
  block.number = block_number;
  auto it = std::find_if(programs_.begin(), programs_.end(), [&](const auto& q) { return q.number == program; });
  if (it == programs_.end()) {
    if (static_cast<int>(programs_.size()) >= limits_.programs) return 137;
    if (blocks_used(ram) + 1 > (ram ? limits_.ram_blocks : limits_.eeprom_blocks)) return 138;
    Wf725Program p;
    p.number = program;
    p.ram = ram;
    p.blocks.push_back(std::move(block));
    programs_.push_back(std::move(p));
    ++revision_;
    return 0;
  }
  auto& blocks = it->blocks;
  const auto at = std::lower_bound(blocks.begin(), blocks.end(), block_number,
                                   [](const Wf725Block& b, int n) { return b.number < n; });
  if (at != blocks.end() && at->number == block_number) {
    *at = std::move(block);
    ++revision_;
    return 0;
  }
  if (blocks_used(it->ram) + 1 > (it->ram ? limits_.ram_blocks : limits_.eeprom_blocks)) return 138;
  blocks.insert(at, std::move(block));
  ++revision_;
  return 0;
}

int Wf725ProgramStore::add_user(InUse in_use) {
  users_.emplace_back(next_user_, std::move(in_use));
  return next_user_++;
}

void Wf725ProgramStore::remove_user(int id) noexcept {
  std::erase_if(users_, [id](const auto& u) { return u.first == id; });
}

bool Wf725ProgramStore::in_use(int number) const {
  return std::any_of(users_.begin(), users_.end(), [number](const auto& u) { return u.second && u.second(number); });
}

}  // namespace hil::controllers::s5
