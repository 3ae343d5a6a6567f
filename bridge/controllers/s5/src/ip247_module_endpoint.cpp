// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_module_endpoint.hpp"

#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

namespace hil::controllers::s5 {

using serial::s5::Rk512Error;
using stepdir::Ip247Error;

Ip247ModulePolicy::Ip247ModulePolicy(Ip247ModuleOptions o) : o_(o) {
  for (std::size_t i = 0; i < 3; ++i) {
    axes_[i] = std::make_unique<Ip247Axis>(programs_, static_cast<int>(i) + 1);
    iface_[i].assign(ip247_axis_db_words, 0);
  }
}

Ip247Inputs Ip247ModulePolicy::inputs(int n) const {
  Ip247Inputs in;
  const Ip247Axis& a = *axes_[static_cast<std::size_t>(n - 1)];
  const auto& sw = o_.switches[static_cast<std::size_t>(n - 1)];
  const std::int64_t p = a.planner() ? a.planner()->motor_position() : 0;
  const bool nc = a.machine_data() && a.machine_data()->limits_normally_closed;
  const bool ls = sw.limit_start_at && p <= *sw.limit_start_at;
  const bool le = sw.limit_end_at && p >= *sw.limit_end_at;
  in.limit_start = nc ? !ls : ls;
  in.limit_end = nc ? !le : le;
  in.reference = sw.cam && p >= sw.cam->first && p <= sw.cam->second;
  return in;
}

void Ip247ModulePolicy::on_time(TimePoint now) {
  if (!started_) {
    started_ = true;
    t_ = now;
    return;
  }
  const auto cycle = o_.cycle;
  if (now - t_ > std::chrono::seconds(60)) t_ = now - std::chrono::seconds(60);  // long idle: bounded catch-up
  while (t_ + cycle <= now) {
    t_ += cycle;
    for (int n = 1; n <= 3; ++n) {
      Ip247Inputs in = inputs(n);
      if (hooks_.inputs) hooks_.inputs(n, in);
      axes_[static_cast<std::size_t>(n - 1)]->step(t_.time_since_epoch().count(), cycle.count(), in, nullptr);
    }
    if (hooks_.after_cycle) hooks_.after_cycle(t_);
  }
}

TimePoint Ip247ModulePolicy::next_deadline() const {
  return started_ ? t_ + o_.cycle : TimePoint::max();
}

Rk512Error Ip247ModulePolicy::on_write(mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                       const std::vector<std::uint16_t>& w) {
  if (dw == 0 && w.size() == 1 && w[0] == 0) {  // delete (BA21 / BA23)
    const auto it = store.find(db);
    if (it == store.end()) return Rk512Error::db_missing;
    if (it->second.size() == ip247_md_words && !it->second.empty() && it->second[0] == 70) {
      for (std::size_t i = 0; i < 3; ++i) {
        if (md_db_[i] == db) {
          if (axes_[i]->delete_machine_data() != Ip247Error::none) return Rk512Error::processing_not_possible;
          md_db_[i] = -1;
        }
      }
    } else if (programs_.erase(db) == Ip247Error::program_active) {
      rejection_ = "program " + std::to_string(db) + " is running (error 51)";
      return Rk512Error::processing_not_possible;
    }
    store.erase(it);
    return Rk512Error::ok;
  }
  if (dw != 0) return Rk512Error::processing_not_possible;  // images are written whole
  if (store.contains(db)) return Rk512Error::db_exists;     // no overwrite: delete first
  if (w.size() < 5 || w[1] != 0x0044 || (w[2] >> 8) != 'B' || (w[2] & 0xFF) != db || w[0] != w.size()) {
    return Rk512Error::wrong_identifier;
  }
  if (w[0] == ip247_md_words) {
    auto md = parse_ip247_md_db(w);
    if (!md || md->axis < 1 || md->axis > 3) {
      rejection_ = "MD DB" + std::to_string(db) + ": MD error " + std::to_string(md ? 0 : static_cast<int>(md.error()));
      return Rk512Error::image_rejected;
    }
    const auto i = static_cast<std::size_t>(md->axis - 1);
    if (md_db_[i] >= 0) return Rk512Error::db_exists;
    const auto e = axes_[i]->load_machine_data(*md, o_.sysid_module);
    if (e != stepdir::Ip247MdError::none) {
      rejection_ = "MD DB" + std::to_string(db) + ": MD error " + std::to_string(static_cast<int>(e)) + " (" +
                   make_error_code(e).message() + ")";
      return Rk512Error::image_rejected;
    }
    md_db_[i] = db;
    store[db] = w;
    return Rk512Error::ok;
  }
  auto vp = parse_ip247_vp_db(w);
  if (!vp) {
    rejection_ = vp.error();
    return Rk512Error::wrong_identifier;
  }
  Ip247SyntaxFault fault;
  const Ip247Error e = programs_.write(db, vp->text, &fault);
  if (e == Ip247Error::program_faulty) {
    rejection_ = "VP DB" + std::to_string(db) + ": error 48, syntax error " +
                 std::to_string(static_cast<int>(fault.code)) + " in block N" + std::to_string(fault.block_number) +
                 ": " + fault.message;
    return Rk512Error::image_rejected;
  }
  if (e != Ip247Error::none) {
    rejection_ = "VP DB" + std::to_string(db) + ": " + make_error_code(e).message();
    return e == Ip247Error::program_exists ? Rk512Error::db_exists : Rk512Error::processing_not_possible;
  }
  store[db] = w;
  return Rk512Error::ok;
}

Rk512Error Ip247ModulePolicy::on_read(const mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                      std::uint16_t length, std::vector<std::uint16_t>& out) {
  const auto it = store.find(db);
  if (it == store.end()) return Rk512Error::db_missing;
  if (std::size_t{dw} + length > it->second.size()) return Rk512Error::target_too_small;
  out.assign(it->second.begin() + dw, it->second.begin() + dw + length);
  return Rk512Error::ok;
}

std::vector<std::uint16_t>& Ip247ModulePolicy::refresh(int n) {
  auto& img = iface_[static_cast<std::size_t>(n - 1)];
  const Ip247Axis& a = axis(n);
  write_ip247_status(img, a, a.machine_data() && a.machine_data()->ag_bcd);
  return img;
}

Rk512Error Ip247ModulePolicy::on_write_dx(mocks::legacy::DbStore&, std::uint8_t dx, std::uint8_t dw,
                                          const std::vector<std::uint16_t>& w) {
  if (dx < 1 || dx > 3) return Rk512Error::db_missing;
  auto& img = iface_[dx - 1U];
  if (std::size_t{dw} + w.size() > ip247_axis_db_words) return Rk512Error::target_too_small;
  std::copy(w.begin(), w.end(), img.begin() + dw);
  Ip247Axis& a = axis(dx);
  const bool bcd = a.machine_data() && a.machine_data()->ag_bcd;
  auto job = take_ip247_job(img, bcd);
  int decode_error = 0;
  if (job) {
    if (*job) {
      a.command(**job);
    } else {
      decode_error = static_cast<int>(job->error());
    }
  }
  refresh(dx);
  if (decode_error != 0) img[12] = static_cast<std::uint16_t>((img[12] & 0xFF00) | decode_error);
  return Rk512Error::ok;
}

Rk512Error Ip247ModulePolicy::on_read_dx(const mocks::legacy::DbStore&, std::uint8_t dx, std::uint8_t dw,
                                         std::uint16_t length, std::vector<std::uint16_t>& out) {
  if (dx < 1 || dx > 3) return Rk512Error::db_missing;
  if (std::size_t{dw} + length > ip247_axis_db_words) return Rk512Error::target_too_small;
  const auto& img = refresh(dx);
  out.assign(img.begin() + dw, img.begin() + dw + length);
  return Rk512Error::ok;
}

void Ip247ModulePolicy::adopt(mocks::legacy::DbStore& store) {
  mocks::legacy::DbStore in;
  in.swap(store);
  for (const auto& [db, w] : in) {
    if (on_write(store, db, 0, w) != Rk512Error::ok) store[db] = w;  // keep what cannot be loaded
  }
}

}  // namespace hil::controllers::s5
