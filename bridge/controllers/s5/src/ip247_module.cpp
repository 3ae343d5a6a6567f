// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_module.hpp"

#include <algorithm>

#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

namespace hil::controllers::s5 {

using stepdir::Ip247Error;
using IfError = Ip247InterfaceError;

namespace {

/// The S5 DB of a directory entry holds only DW0..DW255 (§6.3.8.5).
constexpr std::size_t directory_db_words = 256;

Ip247DataResult failed(Ip247Error e) {
  return {IfError::none, e, 0, 0};
}
Ip247DataResult failed(IfError e) {
  return {e, Ip247Error::none, 0, 0};
}

/// The image header every DB image carries: DW1 = 00h,'D', DW2 = 'B', DB number.
bool identifier_ok(const std::vector<std::uint16_t>& w, int db) {
  return w.size() >= 3 && w[1] == 0x0044 && (w[2] >> 8) == 'B' && (w[2] & 0xFF) == db;
}

/// The image a write job takes from the PLC: its length is the first word (at most `max`).
struct Source {
  IfError error = IfError::none;
  std::vector<std::uint16_t> words;
};
Source take_source(const S5Blocks& plc, int db, int start, std::optional<std::size_t> count, std::size_t max) {
  const auto it = plc.find(db);
  if (it == plc.end()) return {IfError::db_missing, {}};
  const auto& w = it->second;
  if (start < 0 || static_cast<std::size_t>(start) >= w.size()) return {IfError::offset_too_large, {}};
  const auto s = static_cast<std::size_t>(start);
  const std::size_t n = count.value_or(w[s]);
  if (n > max) return {IfError::source_too_large, {}};
  if (n == 0 || s + n > w.size()) return {IfError::source_too_small, {}};
  return {IfError::none, {w.begin() + start, w.begin() + static_cast<std::ptrdiff_t>(s + n)}};
}

void put_dd(std::vector<std::uint16_t>& w, std::size_t i, std::uint32_t v) {
  w[i] = static_cast<std::uint16_t>(v >> 16);
  w[i + 1] = static_cast<std::uint16_t>(v & 0xFFFF);
}

}  // namespace

Ip247Module::Ip247Module(int base_tile, Ip247InterpreterOptions io) : base_tile_(base_tile) {
  for (std::size_t i = 0; i < axes_.size(); ++i)
    axes_[i] = std::make_unique<Ip247Axis>(store_, static_cast<int>(i) + 1, io);
}

int Ip247Module::channel(int tile) const noexcept {
  const int c = tile - base_tile_ + 1;
  return c >= 1 && c <= ip247_data_channel ? c : 0;
}

const std::vector<std::uint16_t>* Ip247Module::md_image(int n) const noexcept {
  const auto i = static_cast<std::size_t>(n - 1);
  return md_db_[i] >= 0 ? &md_images_[i] : nullptr;
}

std::optional<std::vector<std::uint16_t>> Ip247Module::vp_image(int number) const {
  if (const std::string* text = store_.text(number)) {
    auto w = make_ip247_vp_db(Ip247VpImage{static_cast<std::uint8_t>(number), *text, 0, 0});
    if (w) return std::move(*w);
  }
  if (const auto it = refused_vp_.find(number); it != refused_vp_.end()) return it->second;
  return std::nullopt;
}

void Ip247Module::command(int n, const Ip247Job& job) {
  Ip247Axis& a = axis(n);
  const bool was_running = a.running();
  a.command(job);
  if (job.ba == 17 && !was_running) {  // BA17: the errors of all axes and of the data channel
    for (int k = 1; k <= ip247_axes; ++k) axis(k).clear_error();
    data_error_ = 0;
  }
}

Ip247DataResult Ip247Module::write_md(int n, int db, const std::vector<std::uint16_t>& image) {
  if (image.size() != ip247_md_words || image[0] != ip247_md_words || !identifier_ok(image, db))
    return failed(IfError::wrong_identifier);
  if ((image[3] & 0xFF) != n) return failed(Ip247Error::mode_not_allowed_on_axis);  // MD of another axis
  Ip247Axis& a = axis(n);
  if (a.running()) return failed(Ip247Error::axis_running);
  const auto i = static_cast<std::size_t>(n - 1);
  if (md_db_[i] >= 0) return failed(IfError::db_exists);  // no overwrite: BA21 first
  std::vector<std::uint16_t> stored = image;
  auto md = parse_ip247_md_db(image);
  stepdir::Ip247MdError e = md ? a.load_machine_data(*md, sysid_.module) : md.error();
  Ip247Error module_error = Ip247Error::none;
  if (e != stepdir::Ip247MdError::none) {
    // The module keeps the faulty set with its MD error in DR 4; the axis is "not ready".
    a.set_faulty_machine_data(true);
    module_error = a.error() == static_cast<int>(Ip247Error::ramp_table_generation) ? Ip247Error::ramp_table_generation
                                                                                    : Ip247Error::faulty_machine_data;
  }
  stored[4] = static_cast<std::uint16_t>((stored[4] & 0xFF00) | (static_cast<int>(e) & 0xFF));
  md_images_[i] = std::move(stored);
  md_db_[i] = db;
  return {IfError::none, module_error, static_cast<int>(ip247_md_words), 0};
}

Ip247DataResult Ip247Module::md_write(int n, const Ip247DataJob& job, const S5Blocks& plc) {
  auto src = take_source(plc, job.q_db, job.q_start, std::nullopt, ip247_md_words);
  if (src.error != IfError::none) return failed(src.error);
  return write_md(n, job.z_db, src.words);
}

Ip247DataResult Ip247Module::md_delete(int n, int db) {
  Ip247Axis& a = axis(n);
  const auto i = static_cast<std::size_t>(n - 1);
  if (md_db_[i] != db) return failed(Ip247Error::db_not_present);
  if (a.running()) return failed(Ip247Error::axis_running);
  (void)a.delete_machine_data();
  md_images_[i].clear();
  md_db_[i] = -1;
  return {};
}

Ip247DataResult Ip247Module::write_vp(int db, const std::vector<std::uint16_t>& image, Ip247SyntaxFault* fault) {
  if (image.size() < ip247_vp_header_words || !identifier_ok(image, db)) return failed(IfError::wrong_identifier);
  if (store_.teach_axis != 0) return failed(Ip247Error::teach_in_exclusive);
  if (store_.find(db) != nullptr) return failed(Ip247Error::program_exists);
  auto vp = parse_ip247_vp_db(image);
  if (!vp) return failed(IfError::wrong_identifier);
  Ip247SyntaxFault f;
  const Ip247Error e = store_.write(db, vp->text, &f);
  if (e == Ip247Error::program_faulty) {
    std::vector<std::uint16_t> refused = image;
    set_ip247_vp_error(refused, f);
    refused_vp_[db] = std::move(refused);
    if (fault != nullptr) *fault = f;
  }
  if (e != Ip247Error::none) return failed(e);
  refused_vp_.erase(db);
  return {IfError::none, Ip247Error::none, static_cast<int>(image.size()), 0};
}

Ip247DataResult Ip247Module::vp_delete(int db) {
  if (store_.teach_axis != 0) return failed(Ip247Error::teach_in_exclusive);
  if (store_.find(db) == nullptr)
    return refused_vp_.erase(db) != 0 ? Ip247DataResult{} : failed(Ip247Error::db_not_present);
  return failed(store_.erase(db));  // none, 51 (nothing deleted) or the message 61
}

Ip247DataResult Ip247Module::sysid_write(const Ip247DataJob& job, const S5Blocks& plc) {
  auto src = take_source(plc, job.q_db, job.q_start, 3, 3);
  if (src.error != IfError::none) return failed(src.error);
  const Ip247SysId id{src.words[0] & 0xFF, src.words[1] & 0xFF, src.words[2] & 0xFF};
  if (id.module > 99) return failed(Ip247Error::job_not_allowed);  // decision: module numbers are 0..99
  for (int n = 1; n <= ip247_axes; ++n) {
    const auto& md = axis(n).machine_data();
    if (md && md->module != id.module) return failed(Ip247Error::module_number_locked);
  }
  sysid_ = id;
  return {IfError::none, Ip247Error::none, 3, 0};
}

Ip247DataResult Ip247Module::read_into(const std::vector<std::uint16_t>& words, const Ip247DataJob& job,
                                       S5Blocks& plc) const {
  const auto it = plc.find(job.z_db);
  if (it == plc.end()) return failed(IfError::db_missing);
  if (job.z_start < 0) return failed(IfError::offset_too_large);
  const auto s = static_cast<std::size_t>(job.z_start);
  if (s + words.size() > it->second.size()) return failed(IfError::target_too_small);
  std::copy(words.begin(), words.end(), it->second.begin() + job.z_start);
  return {IfError::none, Ip247Error::none, static_cast<int>(words.size()), 0};
}

Ip247DataResult Ip247Module::vp_directory(const Ip247DataJob& job, S5Blocks& plc) const {
  std::vector<std::uint16_t> words;
  for (const auto& [number, length] : store_.directory()) {
    words.push_back(static_cast<std::uint16_t>(number & 0xFF));  // KY 0,dbno
    words.push_back(static_cast<std::uint16_t>(length));         // KF length in words
  }
  const auto x = plc.find(job.z_db);
  if (x == plc.end()) return failed(IfError::db_missing);
  if (job.z_start < 0 || static_cast<std::size_t>(job.z_start) >= directory_db_words)
    return failed(IfError::offset_too_large);
  const auto s = static_cast<std::size_t>(job.z_start);
  if (s + words.size() <= directory_db_words) {
    if (s + words.size() > x->second.size()) return failed(IfError::target_too_small);
    std::copy(words.begin(), words.end(), x->second.begin() + job.z_start);
    return {IfError::none, Ip247Error::none, static_cast<int>(words.size()), 0};
  }
  // Split (§6.3.8.5): whole entries up to DW255 of DBx (which must reach DW255), the rest in DBx+1
  // from DW0; there is no DBx+2.
  const std::size_t first = (directory_db_words - s) / 2 * 2;
  const auto y = plc.find(job.z_db + 1);
  if (x->second.size() < directory_db_words) return failed(IfError::target_too_small);
  if (y == plc.end()) return failed(IfError::db_missing);
  const std::size_t rest = words.size() - first;
  if (rest > directory_db_words || rest > y->second.size()) return failed(IfError::target_too_small);
  std::copy(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(first), x->second.begin() + job.z_start);
  std::copy(words.begin() + static_cast<std::ptrdiff_t>(first), words.end(), y->second.begin());
  return {IfError::none, Ip247Error::none, static_cast<int>(words.size()), 0};
}

Ip247DataResult Ip247Module::actual_values(int n, const Ip247DataJob& job, S5Blocks& plc) const {
  const Ip247Axis& a = axis(n);
  std::vector<std::uint16_t> w(6, 0);
  std::uint8_t flags = 0;
  const auto value = [&](std::int64_t v, std::uint8_t flag) {
    const auto bin = static_cast<std::uint32_t>(static_cast<std::int32_t>(v));
    if (!job.bcd) return bin;
    const auto b = encode_ip247_dd(v, true);
    if (!b) flags |= flag;  // not convertible: binary, flagged in MB249
    return b.value_or(bin);
  };
  if (a.machine_data()) {
    put_dd(w, 0, value(a.actual(), 0x01));
    put_dd(w, 4, value(a.remaining(), 0x02));
  }
  auto r = read_into(w, job, plc);
  if (r.interface_error == IfError::none) r.bcd_flags = flags;
  return r;
}

Ip247DataResult Ip247Module::data_job(const Ip247DataJob& job, S5Blocks& plc) {
  const int ch = channel(job.tile);
  if (ch == 0) return failed(IfError::htb);
  const bool axis_tile = ch <= ip247_axes;
  const Ip247DataResult wrong_tile = failed(Ip247Error::mode_not_allowed_on_axis);
  Ip247DataResult r;
  switch (job.ba) {
    case 20:
      r = axis_tile ? md_write(ch, job, plc) : wrong_tile;
      break;
    case 21:
      r = axis_tile ? md_delete(ch, job.z_db) : wrong_tile;
      break;
    case 22: {
      if (axis_tile) {
        r = wrong_tile;
        break;
      }
      auto src = take_source(plc, job.q_db, job.q_start, std::nullopt, ip247_vp_max_words);
      r = src.error != IfError::none ? failed(src.error) : write_vp(job.z_db, src.words);
      break;
    }
    case 23:
      r = axis_tile ? wrong_tile : vp_delete(job.z_db);
      break;
    case 24:
      r = axis_tile ? wrong_tile : sysid_write(job, plc);
      break;
    case 64: {
      std::vector<std::uint16_t> w(2 * ip247_axes, 0);
      for (int n = 1; n <= ip247_axes; ++n) {
        const auto i = static_cast<std::size_t>(n - 1);
        if (md_db_[i] < 0) continue;
        w[2 * i] = static_cast<std::uint16_t>(md_db_[i]);
        w[2 * i + 1] = static_cast<std::uint16_t>(ip247_md_words);
      }
      r = read_into(w, job, plc);
      break;
    }
    case 65:
      r = vp_directory(job, plc);
      break;
    case 66:
      r = axis_tile ? actual_values(ch, job, plc) : wrong_tile;
      break;
    case 67: {
      int n = 0;
      if (axis_tile) {
        n = md_db_[static_cast<std::size_t>(ch - 1)] == job.q_db ? ch : 0;
      } else {
        // The data channel names the set by its DB number only: every number must differ.
        for (int a = 0; a < ip247_axes; ++a)
          for (int b = a + 1; b < ip247_axes; ++b)
            if (md_db_[static_cast<std::size_t>(a)] >= 0 &&
                md_db_[static_cast<std::size_t>(a)] == md_db_[static_cast<std::size_t>(b)])
              n = -1;
        for (int k = 1; k <= ip247_axes && n == 0; ++k)
          if (md_db_[static_cast<std::size_t>(k - 1)] == job.q_db) n = k;
      }
      if (n < 0) {
        r = wrong_tile;
      } else if (n == 0) {
        r = failed(Ip247Error::db_not_present);
      } else {
        r = read_into(md_images_[static_cast<std::size_t>(n - 1)], job, plc);
      }
      break;
    }
    case 68: {
      std::vector<std::uint16_t> w(5 * ip247_axes, 0);
      for (int n = 1; n <= ip247_axes; ++n) {
        const auto* img = md_image(n);
        if (img == nullptr) continue;
        const auto i = 5 * static_cast<std::size_t>(n - 1);
        w[i] = static_cast<std::uint16_t>(md_db(n));
        w[i + 1] = static_cast<std::uint16_t>((*img)[3] >> 8);
        w[i + 2] = static_cast<std::uint16_t>((*img)[3] & 0xFF);
        w[i + 3] = static_cast<std::uint16_t>(ip247_md_words);
        w[i + 4] = static_cast<std::uint16_t>((*img)[4] & 0xFF);
      }
      r = read_into(w, job, plc);
      break;
    }
    case 69: {
      const auto img = vp_image(job.q_db);
      r = img ? read_into(*img, job, plc) : failed(Ip247Error::db_not_present);
      break;
    }
    case 70: {
      const std::vector<std::uint16_t> w{0x4950,
                                         0x3234,
                                         0x3720,  // "IP247 "
                                         0x4130,
                                         0x322E,
                                         0x3120,  // "A02.1 "
                                         static_cast<std::uint16_t>(sysid_.module),
                                         static_cast<std::uint16_t>(sysid_.slot),
                                         static_cast<std::uint16_t>(sysid_.tile)};
      r = read_into(w, job, plc);
      break;
    }
    default:
      r = failed(job.ba >= 1 && job.ba <= 17 && !axis_tile ? Ip247Error::mode_not_allowed_on_axis
                                                           : Ip247Error::job_not_allowed);
      break;
  }
  const int e = static_cast<int>(r.module_error);
  if (e != 0 && r.interface_error == IfError::none) r.interface_error = IfError::module;
  if (axis_tile) {
    if (e != 0) axis(ch).report(r.module_error);
  } else {
    data_error_ = e;  // the data channel's error: acknowledged by its next job
  }
  return r;
}

std::optional<Ip247DataJob> take_ip247_data_job(const std::vector<std::uint16_t>& block) {
  if (block.size() < ip247_data_job_words || block[0] == 0) return std::nullopt;
  Ip247DataJob j;
  j.ba = block[0] & 0xFF;
  j.bcd = (block[0] >> 8) != 0;
  j.q_db = block[1];
  j.q_start = block[2];
  j.z_db = block[3];
  j.z_start = block[4];
  j.tile = block[5];
  return j;
}

void write_ip247_data_result(std::vector<std::uint16_t>& block, const Ip247DataResult& r) {
  if (block.size() < ip247_data_job_words) block.resize(ip247_data_job_words, 0);
  const auto ie = static_cast<std::uint16_t>(r.interface_error);
  const auto me = static_cast<std::uint16_t>(static_cast<int>(r.module_error) & 0xFF);
  block[0] = 0;
  block[6] = static_cast<std::uint16_t>((me != 0 ? 1 : 0) | (ie != 0 ? 2 : 0));
  block[7] = static_cast<std::uint16_t>((ie << 8) | me);
  block[8] = r.bcd_flags;
  block[9] = static_cast<std::uint16_t>(r.words);
  for (std::size_t i = 10; i < ip247_data_job_words; ++i) block[i] = 0;
}

}  // namespace hil::controllers::s5
