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
  order_.push_back(number);
  used_ += text.size();
  return Ip247Error::none;
}

Ip247Error Ip247ProgramStore::erase(int number) {
  auto it = programs_.find(number);
  if (it == programs_.end()) return Ip247Error::db_not_present;
  if (active(number)) return Ip247Error::program_active;
  used_ -= it->second.text.size();
  programs_.erase(it);
  order_.erase(std::find(order_.begin(), order_.end(), number));
  return Ip247Error::none;
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
  for (int n : order_) {
    const auto words = ip247_vp_header_words + (programs_.at(n).text.size() + 1) / 2;
    d.emplace_back(n, static_cast<int>(words));
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
