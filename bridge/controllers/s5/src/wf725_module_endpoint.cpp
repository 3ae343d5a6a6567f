// SPDX-License-Identifier: MIT
// `hilbridge emulate wf725`: the module's DB axes, MD image and user data blocks over RK512.
#include "hil/controllers/s5/wf725_module_endpoint.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace hil::controllers::s5 {

using serial::s5::Rk512Error;

Wf725ModulePolicy::Wf725ModulePolicy(std::vector<Wf725Controller*> axes, Duration period,
                                     std::function<void(const CycleTime&)> cycle)
    : axes_(std::move(axes)), period_(period), cycle_(std::move(cycle)) {
  // One module: one program memory (digest §6.2: the limits are the module's), combined programs.
  for (auto* a : axes_) {
    if (auto r = module_.add(*a); !r) throw std::invalid_argument("wf725 module: " + r.error());
  }
  if (!axes_.empty()) saved_revision_ = axes_.front()->programs().revision();
}

std::string Wf725ModulePolicy::save_module_state() const {
  if (axes_.empty()) return {};
  std::string text;
  for (const auto& p : axes_.front()->programs().all()) text += make_wf725_program_text(p);
  return text;
}

std::expected<void, std::string> Wf725ModulePolicy::load_module_state(const std::string& text) {
  if (text.empty() || axes_.empty()) return {};
  auto progs = parse_wf725_programs(text);
  if (!progs)
    return std::unexpected(
        fmt::format("state file: the saved program memory does not parse (line {}, program {} N{}: "
                    "{}); the memory keeps the programs given at start",
                    progs.error().line, progs.error().program, progs.error().block, progs.error().message));
  auto& store = *axes_.front()->program_store();
  std::string refused;
  for (auto& p : *progs) {
    if (store.find(p.number) != nullptr) continue;  // given at power-up: that one wins
    const int n = p.number;
    if (const int e = store.store(std::move(p)))
      refused += fmt::format("{}program {} (WF message {})", refused.empty() ? "" : ", ", n, e);
  }
  saved_revision_ = store.revision();
  if (!refused.empty()) return std::unexpected("state file: the program memory refused the saved " + refused);
  return {};
}

bool Wf725ModulePolicy::take_dirty() {
  if (axes_.empty()) return false;
  const auto r = axes_.front()->programs().revision();
  return std::exchange(saved_revision_, r) != r;
}

void Wf725ModulePolicy::share_store(mocks::legacy::DbStore& store) {
  for (auto* a : axes_) a->use_user_blocks(&store);
}

Wf725Controller* Wf725ModulePolicy::axis_of_db(std::uint8_t db) const noexcept {
  for (auto* a : axes_)
    if (a->interface_db().number == db) return a;
  return nullptr;
}

void Wf725ModulePolicy::on_time(TimePoint now) {
  if (!started_) {
    started_ = true;
    t_ = now;
    return;
  }
  // After a long stall (a suspended process) the module catches up at most 1 s: the axes do not
  // replay minutes of motion in a burst.
  if (now - t_ > std::chrono::seconds(1)) t_ = now - std::chrono::seconds(1);
  while (t_ + period_ <= now) {
    t_ += period_;
    cycle_(CycleTime{t_, period_});
  }
}

TimePoint Wf725ModulePolicy::next_deadline() const {
  return started_ ? t_ + period_ : TimePoint::max();
}

Rk512Error Wf725ModulePolicy::on_write(mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                       const std::vector<std::uint16_t>& w) {
  if (auto* a = axis_of_db(db)) {
    if (std::size_t{dw} + w.size() > wf_db::words) {
      rejection_ = fmt::format("DB{} (DB axis) has DW 0..{}", db, wf_db::words - 1);
      return Rk512Error::target_too_small;
    }
    for (std::size_t i = 0; i < w.size(); ++i) (void)a->write_data_word(db, static_cast<int>(dw + i), w[i]);
    return Rk512Error::ok;
  }
  if (db == wf725_md_image_db) {
    if (axes_.empty()) return Rk512Error::db_missing;
    return write_md_image(*axes_.front(), dw, w);
  }
  if (db == 0) {
    rejection_ = "DB0 does not exist";
    return Rk512Error::header_error;
  }
  if (std::size_t{dw} + w.size() > wf725_user_block_words) {
    rejection_ = fmt::format("DB{}: a user data block has DW 0..{}", db, wf725_user_block_words - 1);
    return Rk512Error::target_too_small;
  }
  auto& words = store[db];
  if (words.size() < dw + w.size()) words.resize(dw + w.size(), 0);
  std::copy(w.begin(), w.end(), words.begin() + dw);
  return Rk512Error::ok;
}

Rk512Error Wf725ModulePolicy::on_read(const mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                      std::uint16_t length, std::vector<std::uint16_t>& out) {
  out.clear();
  if (auto* a = axis_of_db(db)) {
    if (std::size_t{dw} + length > wf_db::words) {
      rejection_ = fmt::format("DB{} (DB axis) has DW 0..{}", db, wf_db::words - 1);
      return Rk512Error::target_too_small;
    }
    for (std::uint16_t i = 0; i < length; ++i) out.push_back(a->read_db_word(static_cast<std::uint16_t>(dw + i)));
    return Rk512Error::ok;
  }
  if (db == wf725_md_image_db) {
    if (axes_.empty()) return Rk512Error::db_missing;
    return read_md_image(*axes_.front(), dw, length, out);
  }
  const auto it = store.find(db);
  if (it == store.end()) {
    rejection_ = fmt::format("DB{} does not exist", db);
    return Rk512Error::db_missing;
  }
  if (std::size_t{dw} + length > it->second.size()) {
    rejection_ = fmt::format("DB{} has DW 0..{}", db, it->second.size() - 1);
    return Rk512Error::target_too_small;
  }
  out.assign(it->second.begin() + dw, it->second.begin() + dw + length);
  return Rk512Error::ok;
}

Rk512Error Wf725ModulePolicy::write_md_image(Wf725Controller& a, std::uint8_t dw, const std::vector<std::uint16_t>& w) {
  if ((dw % 2) != 0 || (w.size() % 2) != 0) {
    rejection_ = "MD image: whole MD only (even DW, an even number of words)";
    return Rk512Error::wrong_identifier;
  }
  if (std::size_t{dw} + w.size() > wf725_md_image_words) {
    rejection_ = "MD image: MD number > 50 (WF message 121)";
    return Rk512Error::target_too_small;
  }
  if (!a.machine_data_mode()) {
    rejection_ = fmt::format(
        "machine data of axis {} are written in mode machine data input/output (WF message 201): set D 0.10 in "
        "DB{}",
        a.axis_specs()[0].name, a.interface_db().number);
    return Rk512Error::processing_not_possible;
  }
  for (std::size_t i = 0; i < w.size(); i += 2) {
    const int n = (dw + static_cast<int>(i)) / 2 + 1;
    const auto v = static_cast<std::int32_t>((static_cast<std::uint32_t>(w[i]) << 16) | w[i + 1]);
    (void)a.write_machine_data(n, v);
  }
  return Rk512Error::ok;
}

Rk512Error Wf725ModulePolicy::read_md_image(const Wf725Controller& a, std::uint8_t dw, std::uint16_t length,
                                            std::vector<std::uint16_t>& out) {
  if (std::size_t{dw} + length > wf725_md_image_words) {
    rejection_ = "MD image: MD number > 50 (WF message 121)";
    return Rk512Error::target_too_small;
  }
  for (std::uint16_t i = 0; i < length; ++i) {
    const int word = dw + i;
    const auto v = static_cast<std::uint32_t>(a.read_machine_data(word / 2 + 1));
    out.push_back(static_cast<std::uint16_t>(word % 2 == 0 ? v >> 16 : v & 0xFFFF));
  }
  return Rk512Error::ok;
}

Rk512Error Wf725ModulePolicy::on_write_dx(mocks::legacy::DbStore&, std::uint8_t dx, std::uint8_t dw,
                                          const std::vector<std::uint16_t>& w) {
  if (dx < 1 || dx > axes_.size()) {
    rejection_ = fmt::format("DX{}: the module has DX 1..{} (the MD images of its axes)", dx, axes_.size());
    return Rk512Error::db_missing;
  }
  return write_md_image(*axes_[dx - 1U], dw, w);
}

Rk512Error Wf725ModulePolicy::on_read_dx(const mocks::legacy::DbStore&, std::uint8_t dx, std::uint8_t dw,
                                         std::uint16_t length, std::vector<std::uint16_t>& out) {
  out.clear();
  if (dx < 1 || dx > axes_.size()) {
    rejection_ = fmt::format("DX{}: the module has DX 1..{} (the MD images of its axes)", dx, axes_.size());
    return Rk512Error::db_missing;
  }
  return read_md_image(*axes_[dx - 1U], dw, length, out);
}

}  // namespace hil::controllers::s5
