// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_program_store.hpp"

#include <algorithm>

#include "hil/controllers/s5/ip247_program_db.hpp"

namespace hil::controllers::s5 {

using stepdir::Ip247Error;

Ip247Error Ip247ProgramStore::write(int number, const std::string& text, Ip247SyntaxFault* fault) {
  if (programs_.contains(number)) return Ip247Error::program_exists;
  auto p = parse_ip247_program(text);
  if (!p) {
    if (fault != nullptr) *fault = p.error();
    return Ip247Error::program_faulty;
  }
  if (p->number != number) {
    if (fault != nullptr) *fault = {Ip247SyntaxError::block_type, 0, 1, "header number differs from the DB number"};
    return Ip247Error::program_faulty;
  }
  if (programs_.size() >= ip247_max_programs) return Ip247Error::max_programs;
  if (used_ + text.size() > ip247_memory_chars) return Ip247Error::program_memory_full;
  programs_.emplace(number, Entry{text, std::move(*p)});
  memory_.push_back({number, text.size()});
  used_ += text.size();
  return Ip247Error::none;
}

Ip247Error Ip247ProgramStore::erase(int number) {
  auto it = programs_.find(number);
  if (it == programs_.end()) return Ip247Error::db_not_present;
  if (active(number)) return Ip247Error::program_active;
  programs_.erase(it);
  const auto seg =
      std::find_if(memory_.begin(), memory_.end(), [number](const Segment& s) { return s.number == number; });
  seg->number = -1;
  const auto index = seg - memory_.begin();
  compact();
  const bool gap =
      static_cast<std::size_t>(index) < memory_.size() && memory_[static_cast<std::size_t>(index)].number < 0;
  return gap ? Ip247Error::deleted_from_directory_only : Ip247Error::none;
}

void Ip247ProgramStore::compact() {
  std::size_t keep = 0;  // segments up to the last running program stay where they are
  for (std::size_t i = 0; i < memory_.size(); ++i)
    if (memory_[i].number >= 0 && active(memory_[i].number)) keep = i + 1;
  std::vector<Segment> m(memory_.begin(), memory_.begin() + static_cast<std::ptrdiff_t>(keep));
  for (std::size_t i = keep; i < memory_.size(); ++i)
    if (memory_[i].number >= 0) m.push_back(memory_[i]);
  memory_ = std::move(m);
  used_ = 0;
  for (const Segment& s : memory_) used_ += s.chars;
}

std::size_t Ip247ProgramStore::gap_chars() const noexcept {
  std::size_t n = 0;
  for (const Segment& s : memory_)
    if (s.number < 0) n += s.chars;
  return n;
}

const Ip247Program* Ip247ProgramStore::find(int number) const {
  auto it = programs_.find(number);
  return it == programs_.end() ? nullptr : &it->second.program;
}

const std::string* Ip247ProgramStore::text(int number) const {
  auto it = programs_.find(number);
  return it == programs_.end() ? nullptr : &it->second.text;
}

std::vector<std::pair<int, int>> Ip247ProgramStore::directory() const {
  std::vector<std::pair<int, int>> d;
  for (const Segment& s : memory_) {
    if (s.number < 0) continue;
    const auto words = ip247_vp_header_words + (programs_.at(s.number).text.size() + 1) / 2;
    d.emplace_back(s.number, static_cast<int>(words));
  }
  return d;
}

void Ip247ProgramStore::release(int number) {
  auto it = active_.find(number);
  if (it != active_.end() && --it->second <= 0) active_.erase(it);
}

bool Ip247ProgramStore::active(int number) const {
  return active_.contains(number);
}

}  // namespace hil::controllers::s5
