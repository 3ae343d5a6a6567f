// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_module_endpoint.hpp"

#include <fmt/format.h>

#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

namespace hil::controllers::s5 {

using serial::s5::Rk512Error;
using stepdir::Ip247Error;

Ip247ModulePolicy::Ip247ModulePolicy(Ip247ModuleOptions o)
    : o_(o), module_(o.tile), job_block_(ip247_data_job_words, 0) {
  for (auto& img : iface_) img.assign(ip247_axis_db_words, 0);
  if (o_.sysid_module != 0) {  // the SYS-ID the MD check compares with (BA24 at power-up)
    S5Blocks src{{1, {static_cast<std::uint16_t>(o_.sysid_module), 0, static_cast<std::uint16_t>(o_.tile)}}};
    (void)module_.data_job(Ip247DataJob{.ba = 24, .q_db = 1, .tile = o_.tile + 3}, src);
  }
}

Ip247Inputs Ip247ModulePolicy::inputs(int n) const {
  Ip247Inputs in;
  const Ip247Axis& a = module_.axis(n);
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
      module_.axis(n).step(t_.time_since_epoch().count(), cycle.count(), in, nullptr);
    }
    if (hooks_.after_cycle) hooks_.after_cycle(t_);
  }
}

TimePoint Ip247ModulePolicy::next_deadline() const {
  return started_ ? t_ + o_.cycle : TimePoint::max();
}

Rk512Error Ip247ModulePolicy::delete_image(mocks::legacy::DbStore& store, std::uint8_t db) {
  const auto it = store.find(db);
  if (it == store.end()) return Rk512Error::db_missing;
  S5Blocks none;
  for (int n = 1; n <= ip247_axes; ++n) {
    if (module_.md_db(n) != db) continue;
    const auto r = module_.data_job(Ip247DataJob{.ba = 21, .z_db = db, .tile = o_.tile + n - 1}, none);
    if (r.module_error != Ip247Error::none) {
      rejection_ = fmt::format("MD DB{}: {} (error {})", db, make_error_code(r.module_error).message(),
                               static_cast<int>(r.module_error));
      return Rk512Error::processing_not_possible;
    }
    store.erase(it);
    return Rk512Error::ok;
  }
  const auto r = module_.data_job(Ip247DataJob{.ba = 23, .z_db = db, .tile = o_.tile + 3}, none);
  if (r.module_error != Ip247Error::none && r.module_error != Ip247Error::deleted_from_directory_only) {
    rejection_ = fmt::format("VP DB{}: {} (error {})", db, make_error_code(r.module_error).message(),
                             static_cast<int>(r.module_error));
    return r.module_error == Ip247Error::db_not_present ? Rk512Error::db_missing : Rk512Error::processing_not_possible;
  }
  store.erase(it);
  return Rk512Error::ok;
}

Rk512Error Ip247ModulePolicy::on_write(mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                       const std::vector<std::uint16_t>& w) {
  if (dw == 0 && w.size() == 1 && w[0] == 0) return delete_image(store, db);  // BA21 / BA23
  if (dw != 0) return Rk512Error::processing_not_possible;                    // images are written whole
  if (store.contains(db)) return Rk512Error::db_exists;                       // no overwrite: delete first
  if (w.size() < 5 || w[1] != 0x0044 || (w[2] >> 8) != 'B' || (w[2] & 0xFF) != db || w[0] != w.size()) {
    return Rk512Error::wrong_identifier;
  }
  if (w[0] == ip247_md_words) {  // BA20 on the tile of the image's axis (DR 3)
    const int n = w[3] & 0xFF;
    if (n < 1 || n > ip247_axes) {
      rejection_ = fmt::format("MD DB{}: axis {} (DR 3) is not 1..3", db, n);
      return Rk512Error::image_rejected;
    }
    const auto r = module_.write_md(n, db, w);
    if (r.interface_error == Ip247InterfaceError::db_exists) return Rk512Error::db_exists;  // BA21 first
    if (r.interface_error != Ip247InterfaceError::none) return Rk512Error::wrong_identifier;
    if (r.module_error == Ip247Error::faulty_machine_data || r.module_error == Ip247Error::ramp_table_generation) {
      const auto* img = module_.md_image(n);
      const int e = img != nullptr ? (*img)[4] & 0xFF : 0;
      rejection_ = fmt::format("MD DB{}: MD error {} ({})", db, e,
                               make_error_code(static_cast<stepdir::Ip247MdError>(e)).message());
      // Our RK512 mapping stores no refused image: the module's faulty set goes again (BA21).
      S5Blocks none;
      (void)module_.data_job(Ip247DataJob{.ba = 21, .z_db = db, .tile = o_.tile + n - 1}, none);
      return Rk512Error::image_rejected;
    }
    if (r.module_error != Ip247Error::none) {
      rejection_ = fmt::format("MD DB{}: {} (error {})", db, make_error_code(r.module_error).message(),
                               static_cast<int>(r.module_error));
      return Rk512Error::processing_not_possible;
    }
    store[db] = w;
    return Rk512Error::ok;
  }
  Ip247SyntaxFault fault;
  const auto r = module_.write_vp(db, w, &fault);  // BA22
  if (r.interface_error != Ip247InterfaceError::none) {
    rejection_ = fmt::format("VP DB{}: not a VP image (length word, 0044h, 'B' DB, header)", db);
    return Rk512Error::wrong_identifier;
  }
  if (r.module_error == Ip247Error::program_faulty) {
    rejection_ = "VP DB" + std::to_string(db) + ": error 48, syntax error " +
                 std::to_string(static_cast<int>(fault.code)) + " in block N" + std::to_string(fault.block_number) +
                 ": " + fault.message;
    return Rk512Error::image_rejected;
  }
  if (r.module_error != Ip247Error::none) {
    rejection_ = "VP DB" + std::to_string(db) + ": " + make_error_code(r.module_error).message();
    return r.module_error == Ip247Error::program_exists ? Rk512Error::db_exists : Rk512Error::processing_not_possible;
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

Rk512Error Ip247ModulePolicy::on_write_dx(mocks::legacy::DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                          const std::vector<std::uint16_t>& w) {
  if (dx == 0) return Rk512Error::db_missing;
  if (dx >= ip247_first_plc_dx) {  // the PLC's DB dx: created or extended by the SEND
    auto& b = (*plc_)[dx];
    if (b.size() < std::size_t{dw} + w.size()) b.resize(std::size_t{dw} + w.size(), 0);
    std::copy(w.begin(), w.end(), b.begin() + dw);
    return Rk512Error::ok;
  }
  if (dx == ip247_job_block_dx) {
    if (std::size_t{dw} + w.size() > ip247_data_job_words) return Rk512Error::target_too_small;
    std::copy(w.begin(), w.end(), job_block_.begin() + dw);
    return job_block_written(store);
  }
  auto& img = iface_[dx - 1U];
  if (std::size_t{dw} + w.size() > ip247_axis_db_words) return Rk512Error::target_too_small;
  std::copy(w.begin(), w.end(), img.begin() + dw);
  Ip247Axis& a = axis(dx);
  const bool bcd = a.machine_data() && a.machine_data()->ag_bcd;
  auto job = take_ip247_job(img, bcd);
  int decode_error = 0;
  if (job) {
    if (*job) {
      module_.command(dx, **job);
    } else {
      decode_error = static_cast<int>(job->error());
    }
  }
  refresh(dx);
  if (decode_error != 0) img[12] = static_cast<std::uint16_t>((img[12] & 0xFF00) | decode_error);
  return Rk512Error::ok;
}

Rk512Error Ip247ModulePolicy::job_block_written(mocks::legacy::DbStore& store) {
  const auto job = take_ip247_data_job(job_block_);
  if (!job) return Rk512Error::ok;  // parameters only: the job starts with DW0 = BA
  // The images the module holds before and after the job: the endpoint's DB store follows them.
  mocks::legacy::DbStore before;
  mirror(before);
  const auto r = module_.data_job(*job, *plc_);
  write_ip247_data_result(job_block_, r);
  if (r.module_error != Ip247Error::none || r.interface_error != Ip247InterfaceError::none)
    rejection_ = fmt::format("data job BA{}: MB250 {} MB251 {} ({})", job->ba, static_cast<int>(r.interface_error),
                             static_cast<int>(r.module_error), make_error_code(r.module_error).message());
  for (const auto& [db, w] : before) store.erase(db);
  mirror(store);
  return Rk512Error::ok;
}

void Ip247ModulePolicy::mirror(mocks::legacy::DbStore& store) const {
  for (int n = 1; n <= ip247_axes; ++n)
    if (const auto* img = module_.md_image(n)) store[static_cast<std::uint8_t>(module_.md_db(n))] = *img;
  for (const auto& [number, words] : module_.programs().directory()) {
    (void)words;
    if (auto img = module_.vp_image(number)) store[static_cast<std::uint8_t>(number)] = std::move(*img);
  }
}

Rk512Error Ip247ModulePolicy::on_read_dx(const mocks::legacy::DbStore&, std::uint8_t dx, std::uint8_t dw,
                                         std::uint16_t length, std::vector<std::uint16_t>& out) {
  const std::vector<std::uint16_t>* words = nullptr;
  if (dx == 0) return Rk512Error::db_missing;
  if (dx >= ip247_first_plc_dx) {
    const auto it = plc_->find(dx);
    if (it == plc_->end()) return Rk512Error::db_missing;
    words = &it->second;
  } else if (dx == ip247_job_block_dx) {
    words = &job_block_;
  } else {
    words = &refresh(dx);
  }
  if (std::size_t{dw} + length > words->size()) return Rk512Error::target_too_small;
  out.assign(words->begin() + dw, words->begin() + dw + length);
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
