// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <numeric>
#include <set>
#include <sstream>

#include "hil/controllers/io_address_s5.hpp"
#include "hil/controllers/s5/ip247_data_job.hpp"
#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"
#include "hil/profiles/loader.hpp"
#include "hil/serial/s5/db_listing.hpp"

namespace hil::controllers::s5 {

namespace {

namespace hc = hil::controllers;

/// Bits of axis k's input and output bytes (byte k-1).
constexpr std::uint8_t in_limit_start = 0;
constexpr std::uint8_t in_limit_end = 1;
constexpr std::uint8_t in_reference = 2;
constexpr std::uint8_t in_external_stop = 3;
constexpr std::uint8_t out_in_position = 0;
constexpr std::uint8_t out_moving = 1;
constexpr std::uint8_t out_error = 2;
hc::BitAddress in_bit(std::size_t module, int axis, std::uint8_t bit) {
  return {hc::IoArea::input, static_cast<std::uint32_t>(module * ip247_axes + static_cast<std::size_t>(axis - 1)), bit};
}
hc::BitAddress out_bit(std::size_t module, int axis, std::uint8_t bit) {
  return {hc::IoArea::output, static_cast<std::uint32_t>(module * ip247_axes + static_cast<std::size_t>(axis - 1)),
          bit};
}
/// At most this many modules in one controller (decision: 8 modules = 24 axes, SSNR 0..31 from tile 0).
constexpr std::size_t max_modules = 8;

/// The interface DB: three axis DBs of 20 words (FB164, next axis at n+20), then the FB165 job block.
constexpr std::size_t data_job_dw = ip247_axes * ip247_axis_db_words;
constexpr std::size_t interface_words = data_job_dw + ip247_data_job_words;
constexpr std::uint32_t interface_bytes = 2 * interface_words;

std::expected<std::string, ConfigError> read_text(const std::filesystem::path& file, const ControllerSpec& spec,
                                                  std::string_view key) {
  std::ifstream in(file, std::ios::binary);
  if (!in)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, fmt::format("controller.{}", key),
                                       fmt::format("cannot read the file '{}'", file.string())});
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A DB listing starts (after blank lines) with a ';' comment or a "DBn" line.
bool is_db_listing(std::string_view text) {
  const auto p = text.find_first_not_of(" \t\r\n");
  if (p == std::string_view::npos) return false;
  return text[p] == ';' || (text.size() > p + 2 && std::toupper(static_cast<unsigned char>(text[p])) == 'D' &&
                            std::toupper(static_cast<unsigned char>(text[p + 1])) == 'B' &&
                            std::isdigit(static_cast<unsigned char>(text[p + 2])) != 0);
}

/// "file:12: message" of parse_db_listing -> ConfigError at that line.
ConfigError listing_error(const std::vector<std::string>& errors, const std::filesystem::path& file,
                          std::string_view key) {
  const std::string& m = errors.front();
  int line = 0;
  const auto prefix = file.string() + ":";
  std::string text = m;
  if (m.starts_with(prefix)) {
    const auto rest = std::string_view(m).substr(prefix.size());
    const auto colon = rest.find(':');
    (void)std::from_chars(rest.data(), rest.data() + colon, line);
    text = std::string(rest.substr(colon == std::string_view::npos ? 0 : colon + 1));
    while (!text.empty() && text.front() == ' ') text.erase(0, 1);
  }
  return ConfigError{file.string(), line, 0, std::string(key), text};
}

/// The program number of the header ("%  7 title", "L9 sub"); nullopt when there is none.
std::optional<int> header_number(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\r' || text[i] == '\n')) ++i;
  if (i >= text.size() || (text[i] != '%' && text[i] != 'L')) return std::nullopt;
  ++i;
  while (i < text.size() && text[i] == ' ') ++i;
  int n = -1;
  const auto r = std::from_chars(text.data() + i, text.data() + text.size(), n);
  if (r.ec != std::errc{} || n < 0 || n > ip247_max_program_number) return std::nullopt;
  return n;
}

std::expected<int, ConfigError> option_int(const ControllerSpec& spec, std::string_view key, int lo, int hi,
                                           int fallback) {
  const auto it = spec.options.find(key);
  if (it == spec.options.end()) return fallback;
  int v = 0;
  const auto& s = it->second;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size() || v < lo || v > hi)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, fmt::format("controller.{}", key),
                                       fmt::format("expected a number {}..{}, got '{}'", lo, hi, s)});
  return v;
}

}  // namespace

std::expected<std::unique_ptr<hc::Controller>, ConfigError> Ip247Controller::create(const ControllerSpec& spec) {
  for (const auto& [k, v] : spec.options) {
    if (k != "axis" && k != "interface_db" && k != "sysid_module" && k != "plc_dbs" && k != "tile")
      return std::unexpected(ConfigError{
          spec.file, spec.line, 0, "controller." + k,
          fmt::format("unknown key '{}' of the ip247 controller (allowed: device, parameters, programs, cycle, axis, "
                      "interface_db, sysid_module, plc_dbs, tile)",
                      k)});
  }
  auto profile = profiles::find_profile("ip247");
  if (!profile) return std::unexpected(profile.error());
  auto interface_db = option_int(spec, "interface_db", 1, 255, 10);
  if (!interface_db) return std::unexpected(interface_db.error());
  auto sysid = option_int(spec, "sysid_module", 0, 99, 0);
  if (!sysid) return std::unexpected(sysid.error());
  auto tile = option_int(spec, "tile", 0, 252, 0);
  if (!tile) return std::unexpected(tile.error());
  if (*tile % 4 != 0)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.tile",
                                       fmt::format("the IP247 tile base (switch S2) is a multiple of 4 "
                                                   "(0, 4, ... 252), got {}",
                                                   *tile)});

  // The MD DBs: a STEP 5 DB listing with one 70-word image per axis the module has at start.
  auto text = read_text(spec.parameters, spec, "parameters");
  if (!text) return std::unexpected(text.error());
  auto dbs = serial::s5::parse_db_listing(*text, spec.parameters.string());
  if (!dbs) return std::unexpected(listing_error(dbs.error(), spec.parameters, "controller.parameters"));
  std::vector<std::pair<int, Ip247MachineData>> mds;
  std::vector<std::pair<int, std::vector<std::uint16_t>>> md_images;
  for (const auto& d : *dbs) {
    if (d.words.size() != ip247_md_words) continue;
    auto md = parse_ip247_md_db(d.words);
    if (!md)
      return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                         fmt::format("DB{}: IP247 MD error {}: {}", d.db, static_cast<int>(md.error()),
                                                     make_error_code(md.error()).message())});
    if (md->axis < 1 || md->axis > ip247_axes)
      return std::unexpected(
          ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                      fmt::format("DB{}: the axis number (DR 3) is {}; the IP247 has axes 1..3", d.db, md->axis)});
    for (const auto& [db, other] : mds)
      if (other.axis == md->axis && other.module == md->module)
        return std::unexpected(ConfigError{
            spec.parameters.string(), 0, 0, "controller.parameters",
            fmt::format("DB{} and DB{} are both MD of axis {} of module {}: one MD set per axis (DL 3 is the module "
                        "number, DR 3 the axis)",
                        db, d.db, md->axis, md->module)});
    mds.emplace_back(d.db, *md);
    md_images.emplace_back(d.db, d.words);
  }
  if (mds.empty())
    return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                       "no 70-word IP247 machine-data DB in the listing (DW0 = KF +00070)"});
  std::ranges::sort(mds, {}, [](const auto& p) { return std::pair{p.second.module, p.second.axis}; });
  // The modules: the module numbers of the MD sets (DL 3), ascending.
  std::vector<int> module_numbers;
  for (const auto& [db, md] : mds)
    if (std::ranges::find(module_numbers, md.module) == module_numbers.end()) module_numbers.push_back(md.module);
  const std::size_t modules = module_numbers.size();
  if (modules > max_modules)
    return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                       fmt::format("the MD sets name {} module numbers (DL 3); one ip247 controller "
                                                   "holds at most {} modules",
                                                   modules, max_modules)});
  if (modules > 1 && spec.options.contains("sysid_module"))
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.sysid_module",
                                       "with several modules each module's SYS-ID is the module number of its MD sets "
                                       "(DL 3): drop sysid_module"});
  if (*tile + 4 * static_cast<int>(modules) - 1 > 255 || *interface_db + static_cast<int>(modules) - 1 > 255)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.tile",
                                       fmt::format("{} modules need SSNR {}..{} and interface DBs {}..{} (at most 255)",
                                                   modules, *tile, *tile + 4 * static_cast<int>(modules) - 1,
                                                   *interface_db, *interface_db + static_cast<int>(modules) - 1)});
  const auto module_index = [&](int number) {
    return static_cast<std::size_t>(std::ranges::find(module_numbers, number) - module_numbers.begin());
  };
  if (spec.options.contains("axis") && mds.size() > 1)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.axis",
                                       "'axis' names the machine axis of a one-axis module; with several MD sets the "
                                       "machine axes are named by their module axis numbers 1..3"});
  const auto is_interface = [&](int db) { return db >= *interface_db && db < *interface_db + int(modules); };
  for (const auto& [db, md] : mds)
    if (is_interface(db))
      return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.interface_db",
                                         fmt::format("DB{} is the machine-data DB: give the interface DB{} another "
                                                     "number",
                                                     db, db)});

  // The PLC's DBs: sources and targets of the data jobs.
  S5Blocks plc;
  if (const auto it = spec.options.find("plc_dbs"); it != spec.options.end()) {
    std::filesystem::path file(it->second);
    if (file.is_relative() && !spec.file.empty()) file = std::filesystem::path(spec.file).parent_path() / file;
    auto t = read_text(file, spec, "plc_dbs");
    if (!t) return std::unexpected(t.error());
    auto images = serial::s5::parse_db_listing(*t, file.string());
    if (!images) return std::unexpected(listing_error(images.error(), file, "controller.plc_dbs"));
    for (auto& im : *images) {
      if (is_interface(im.db))
        return std::unexpected(
            ConfigError{file.string(), 0, 0, "controller.plc_dbs",
                        fmt::format("DB{} is the interface DB: give the PLC's DB another number", im.db)});
      if (!plc.emplace(im.db, std::move(im.words)).second)
        return std::unexpected(
            ConfigError{file.string(), 0, 0, "controller.plc_dbs", fmt::format("DB{} is given twice", im.db)});
    }
  }

  // The programs: VP DBs the PLC writes at start, by program number.
  std::vector<Ip247ProgramFile> programs;
  std::set<int> numbers;
  for (const auto& file : spec.programs) {
    auto p = read_text(file, spec, "programs");
    if (!p) return std::unexpected(p.error());
    std::vector<Ip247ProgramFile> found;
    if (is_db_listing(*p)) {
      auto images = serial::s5::parse_db_listing(*p, file.string());
      if (!images) return std::unexpected(listing_error(images.error(), file, "program"));
      for (const auto& im : *images) {
        auto vp = parse_ip247_vp_db(im.words);
        if (!vp)
          return std::unexpected(ConfigError{file.string(), 0, 0, "program",
                                             fmt::format("DB{} is not a VP DB image: {}", im.db, vp.error())});
        found.push_back({file, im.db, vp->text});
      }
    } else {
      const auto n = header_number(*p);
      if (!n)
        return std::unexpected(ConfigError{file.string(), 1, 1, "program",
                                           "the first line must be the program header '%n' or 'Ln' (n = 0..255), "
                                           "e.g. '%1 drilling'"});
      found.push_back({file, *n, *p});
    }
    for (auto& f : found) {
      const bool md_number = std::ranges::any_of(mds, [&](const auto& m) { return m.first == f.number; });
      if (is_interface(f.number) || md_number)
        return std::unexpected(
            ConfigError{file.string(), 1, 1, "program",
                        fmt::format("program {} would be DB{}, which is the {} DB: use another program number",
                                    f.number, f.number, is_interface(f.number) ? "interface" : "machine-data")});
      if (!numbers.insert(f.number).second)
        return std::unexpected(
            ConfigError{file.string(), 1, 1, "program",
                        fmt::format("program {} is given twice (error 49: no overwrite)", f.number)});
      programs.push_back(std::move(f));
    }
  }

  const Duration cycle = spec.cycle.value_or(std::chrono::milliseconds(2));
  auto c = std::make_unique<Ip247Controller>(*profile, *interface_db, std::move(programs), std::move(plc), cycle, *tile,
                                             static_cast<int>(modules));
  // The SYS-ID the PLC (or COM247) wrote before the MD (BA24): sysid_module, or with several
  // modules the module number of each module's MD sets.
  for (std::size_t k = 0; k < modules; ++k) {
    const int id_number = modules == 1 ? *sysid : module_numbers[k];
    const int base = *tile + 4 * static_cast<int>(k);
    S5Blocks id{{0, {static_cast<std::uint16_t>(id_number), 0, static_cast<std::uint16_t>(base)}}};
    (void)c->modules_[k]->data_job(Ip247DataJob{24, false, 0, 0, 0, 0, base + 3}, id);
  }
  for (const auto& [db, words] : md_images) {
    const int n = words[3] & 0xFF;
    auto& m = *c->modules_[modules == 1 ? 0 : module_index(words[3] >> 8)];
    const auto r = m.write_md(n, db, words);
    if (r.module_error != stepdir::Ip247Error::none || r.interface_error != Ip247InterfaceError::none) {
      const int md_error = m.md_image(n) != nullptr ? ((*m.md_image(n))[4] & 0xFF) : 0;
      return std::unexpected(
          ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                      fmt::format("DB{}: IP247 MD error {}: {}", db, md_error,
                                  make_error_code(static_cast<stepdir::Ip247MdError>(md_error)).message())});
    }
  }
  c->write_programs();

  // One machine axis per MD set: the motor behind the axis' pulse output, 1 increment = 1 pulse.
  for (const auto& [db, md_ref] : mds) {
    const Ip247MachineData& md = md_ref;
    hc::ControllerAxis a;
    const std::size_t k = module_index(md.module);
    a.name = spec.options.contains("axis") ? spec.options.find("axis")->second
             : modules == 1                ? std::to_string(md.axis)
                                           : fmt::format("m{}a{}", md.module, md.axis);
    const std::int64_t bu_per_unit = md.unit == Ip247Unit::inch ? 10'000 : 1'000;
    a.units = md.unit == Ip247Unit::inch ? "inch" : md.unit == Ip247Unit::degree ? "deg" : "mm";
    auto& cfg = a.config;
    cfg.name = a.name;
    const std::int64_t num = std::int64_t{md.pulses_per_rev} * bu_per_unit;
    const std::int64_t g = std::gcd(num, std::int64_t{md.gear_bu_per_rev});
    cfg.inc_per_unit = {num / g, md.gear_bu_per_rev / g};
    const double ipu = static_cast<double>(num) / static_cast<double>(md.gear_bu_per_rev);
    cfg.limits.velocity = static_cast<double>(md.fmax_hz) / ipu;
    cfg.limits.acceleration = static_cast<double>(md.accel_mhz_per_ms) / ipu;  // mHz/ms = Hz/s
    cfg.quick_stop_deceleration = cfg.limits.acceleration;
    cfg.jog_velocity = std::min(cfg.limits.velocity, static_cast<double>(md.jog1) / 60.0);
    if (md.rotary) {
      cfg.rotary = true;
      cfg.modulo = static_cast<double>(md.sw_end - md.sw_start) / static_cast<double>(bu_per_unit);
    }
    // The module supervises its own limits (SW limits 28/29, limit switches 25/26) and plans the
    // motion; the motion core only follows and guards the plant (50 ms of travel at vmax).
    const double pulse = 1.0 / ipu;
    cfg.following_error.static_window = std::max(0.05 * cfg.limits.velocity, 10.0 * pulse);
    cfg.standstill_window = std::max(2.0 * pulse, 1e-9);
    cfg.in_position_window = pulse;
    cfg.reaction = motion::FaultReaction::stop;
    a.warnings.push_back(
        "the IP247 module plans the motion (its exponential ramp, the programmed speeds) and supervises software "
        "limits, limit switches, backlash and offsets itself; the machine axis follows its pulses from its own zero");
    if (const auto v = motion::validate(cfg); !v)
      return std::unexpected(
          ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                      fmt::format("DB{}: the machine data give an axis the motion core rejects: {}", db, v.error())});
    const std::string& n = a.name;
    auto& io = c->io();
    for (const auto& [name, bit] : {std::pair{"limit_minus_" + n, in_bit(k, md.axis, in_limit_start)},
                                    {"limit_plus_" + n, in_bit(k, md.axis, in_limit_end)},
                                    {"reference_cam_" + n, in_bit(k, md.axis, in_reference)},
                                    {"external_stop_" + n, in_bit(k, md.axis, in_external_stop)},
                                    {"in_position_" + n, out_bit(k, md.axis, out_in_position)},
                                    {"moving_" + n, out_bit(k, md.axis, out_moving)},
                                    {"error_" + n, out_bit(k, md.axis, out_error)}}) {
      if (auto r = io.name_bit(name, bit); !r)
        return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.axis", r.error()});
    }
    c->add_axis(std::move(a));
    c->axes_.push_back({k, md.axis});
  }
  c->followers_.resize(c->axes_.size());
  c->shown_error_.assign(c->axes_.size(), 0);
  c->publish_status();
  return std::unique_ptr<hc::Controller>(std::move(c));
}

Ip247Controller::Ip247Controller(std::shared_ptr<const profiles::Profile> profile, int interface_db,
                                 std::vector<Ip247ProgramFile> programs, S5Blocks plc_dbs, Duration cycle, int tile,
                                 int modules)
    : hc::Controller(std::move(profile), profiles::ParameterSet{},
                     hc::IoLayout{{static_cast<std::uint32_t>(ip247_axes * std::max(modules, 1)),
                                   static_cast<std::uint32_t>(ip247_axes * std::max(modules, 1)), 1,
                                   interface_bytes * static_cast<std::uint32_t>(std::max(modules, 1))}},
                     cycle),
      program_files_(std::move(programs)),
      plc_(std::move(plc_dbs)) {
  for (int k = 0; k < std::max(modules, 1); ++k) {
    interfaces_.push_back(S5DataBlock{static_cast<std::uint16_t>(interface_db + k),
                                      static_cast<std::uint32_t>(k) * interface_bytes,
                                      static_cast<std::uint16_t>(interface_words)});
    modules_.push_back(std::make_unique<Ip247Module>(tile + 4 * k));
  }
  shown_data_error_.assign(modules_.size(), 0);
  words_.assign(interface_words * modules_.size(), 0);
  publish_status();
}

std::size_t Ip247Controller::machine_axis(std::size_t k, int n) const noexcept {
  for (std::size_t i = 0; i < axes_.size(); ++i)
    if (axes_[i].module == k && axes_[i].axis == n) return i;
  return axis_count();
}

void Ip247Controller::publish_status() noexcept {
  std::vector<std::uint16_t> block(ip247_axis_db_words, 0);
  for (std::size_t k = 0; k < modules_.size(); ++k) {
    const std::size_t mbase = k * interface_words;
    for (int n = 1; n <= ip247_axes; ++n) {
      const auto base = mbase + static_cast<std::size_t>(n - 1) * ip247_axis_db_words;
      std::copy_n(words_.begin() + static_cast<std::ptrdiff_t>(base), ip247_axis_db_words, block.begin());
      const Ip247Axis& a = modules_[k]->axis(n);
      write_ip247_status(block, a, a.machine_data() && a.machine_data()->ag_bcd);
      std::copy(block.begin(), block.end(), words_.begin() + static_cast<std::ptrdiff_t>(base));
    }
    for (std::size_t w = 0; w < interface_words; ++w)
      (void)Controller::write_data_word(interfaces_[k].number, static_cast<int>(w), words_[mbase + w]);
  }
}

std::expected<hc::BitAddress, std::string> Ip247Controller::resolve_bit(std::string_view text) const {
  if (auto named = hc::Controller::resolve_bit(text)) return named;
  auto a = hc::parse_s5_address(text, interfaces_.front().number);
  if (!a) return std::unexpected(a.error());
  return hc::to_bit_address(*a, data_blocks());
}

std::expected<std::uint16_t, std::string> Ip247Controller::read_data_word(int db, int dw) const {
  for (const auto& i : interfaces_)
    if (db == i.number) return Controller::read_data_word(db, dw);
  std::optional<std::vector<std::uint16_t>> image;
  if (const auto it = plc_.find(db); it != plc_.end()) {
    image = it->second;
  } else {
    for (const auto& m : modules_) {
      for (int n = 1; n <= ip247_axes && !image; ++n)
        if (m->md_db(n) == db) image = *m->md_image(n);
      if (!image) image = m->vp_image(db);
      if (image) break;
    }
  }
  if (!image) {
    std::string list;
    for (const auto& i : interfaces_) list += fmt::format("{}DB{} (interface)", list.empty() ? "" : ", ", i.number);
    for (const auto& [n, w] : plc_) list += fmt::format(", DB{} (PLC)", n);
    for (const auto& m : modules_) {
      for (int n = 1; n <= ip247_axes; ++n)
        if (m->md_db(n) >= 0) list += fmt::format(", DB{} (machine data of axis {})", m->md_db(n), n);
      for (const auto& [n, len] : m->programs().directory()) list += fmt::format(", DB{} (program {})", n, n);
    }
    return std::unexpected(fmt::format("the ip247 module has no DB{} (it has {})", db, list));
  }
  if (dw < 0 || static_cast<std::size_t>(dw) >= image->size())
    return std::unexpected(
        fmt::format("DB{} of the ip247 module has data words 0..{}; DW {} is beyond it", db, image->size() - 1, dw));
  return (*image)[static_cast<std::size_t>(dw)];
}

std::expected<void, std::string> Ip247Controller::write_data_word(int db, int dw, std::uint16_t value) {
  if (const auto it = plc_.find(db); it != plc_.end()) {
    if (dw < 0 || static_cast<std::size_t>(dw) >= it->second.size())
      return std::unexpected(
          fmt::format("the PLC's DB{} has data words 0..{}; DW {} is beyond it", db, it->second.size() - 1, dw));
    it->second[static_cast<std::size_t>(dw)] = value;
    return {};
  }
  for (const auto& i : interfaces_)
    if (db == i.number) return Controller::write_data_word(db, dw, value);
  return std::unexpected(fmt::format(
      "DB{} of the ip247 module is not written word by word: the PLC writes the interface DB{} and its own DBs "
      "(plc_dbs:); the MD and VP DBs are images the module takes as a whole (data jobs BA20/22 from a PLC DB, or "
      "'parameters:' and 'programs:')",
      db, interfaces_.front().number));
}

std::vector<std::string> Ip247Controller::trace_signals() const {
  std::vector<std::string> names;
  const auto specs = axis_specs();
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    const std::string suffix = axes_.size() == 1 ? "" : "_" + specs[i].name;
    for (const char* s : {"actual_value_BU", "error_number", "m_output"}) names.push_back(s + suffix);
  }
  return names;
}

double Ip247Controller::trace_value(std::size_t i) const noexcept {
  if (i / 3 >= axes_.size()) return 0.0;
  const Ip247Axis& a = module_axis(i / 3);
  switch (i % 3) {
    case 0:
      return static_cast<double>(a.actual());
    case 1:
      return a.error();
    default:
      return a.m_output();
  }
}

void Ip247Controller::write_programs() {
  for (std::size_t k = 0; k < modules_.size(); ++k) {
    for (const auto& f : program_files_) {
      auto image = make_ip247_vp_db(Ip247VpImage{static_cast<std::uint8_t>(f.number), f.text, 0, 0});
      Ip247SyntaxFault fault;
      const auto r = image ? modules_[k]->write_vp(f.number, *image, &fault)
                           : Ip247DataResult{Ip247InterfaceError::source_too_large, stepdir::Ip247Error::none, 0, 0};
      if (r.module_error == stepdir::Ip247Error::none && r.interface_error == Ip247InterfaceError::none) continue;
      if (k > 0) continue;  // every module refuses it the same way: reported once
      const int code = r.module_error != stepdir::Ip247Error::none
                           ? static_cast<int>(r.module_error)
                           : static_cast<int>(stepdir::Ip247Error::program_faulty);
      refused_.push_back(
          {code, r.module_error == stepdir::Ip247Error::program_faulty
                     ? fmt::format("program {} ({}): syntax error {} in block N{}: {}", f.number, f.file.string(),
                                   static_cast<int>(fault.code), fault.block_number, fault.message)
                     : fmt::format("program {} ({}) not stored: {}", f.number, f.file.string(),
                                   image ? make_error_code(r.module_error).message() : image.error())});
    }
  }
}

void Ip247Controller::report_errors(TimePoint now) noexcept {
  const auto* cat = catalogue("module");
  if (cat == nullptr) return;
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    const Ip247Axis& a = module_axis(i);
    const int e = a.error() >= 10 ? a.error() : 0;
    if (e == shown_error_[i]) continue;
    if (shown_error_[i] != 0) (void)clear_error(*cat, shown_error_[i], static_cast<int>(i));
    if (e != 0)
      raise(*cat, e, now, static_cast<int>(i),
            fmt::format("axis {}, BA {}, actual value {} BU", axis_specs()[i].name, a.ba(), a.actual()),
            hc::AckRule::self_clearing, false);
    shown_error_[i] = e;
  }
  // The data channel's error (a data job refused: 48, 49, 13 ...), until its next job or BA17.
  for (std::size_t k = 0; k < modules_.size(); ++k) {
    const int d = modules_[k]->data_channel_error() >= 10 ? modules_[k]->data_channel_error() : 0;
    if (d == shown_data_error_[k]) continue;
    if (shown_data_error_[k] != 0) (void)clear_error(*cat, shown_data_error_[k], -1);
    if (d != 0)
      raise(*cat, d, now, -1,
            modules_.size() == 1 ? std::string("data channel") : fmt::format("data channel of module {}", k),
            hc::AckRule::self_clearing, false);
    shown_data_error_[k] = d;
  }
}

void Ip247Controller::on_cycle(const CycleTime& cycle) noexcept {
  const std::int64_t now_ns = cycle.now.time_since_epoch().count();
  period_ns_ = cycle_period().count();
  // BB: the power section is the machine axis; the module enables it at power-up.
  const bool ready = power_up_axes();
  if (!started_) {
    // The VP DBs the PLC wrote at start that the module refused (error 48 ...).
    if (const auto* cat = catalogue("module"))
      for (const auto& [code, context] : refused_) raise(*cat, code, cycle.now, 0, context, std::nullopt, false);
    started_ = true;
  }
  std::vector<std::uint16_t> block(ip247_axis_db_words, 0);
  for (std::size_t k = 0; k < modules_.size(); ++k) {
    Ip247Module& m = *modules_[k];
    const std::size_t mbase = k * interface_words;
    // The PLC's jobs: BA, parameters and a command bit in each axis DB; a data job in the job block.
    // Until the power section is up at power-on the module takes no job (the PLC's handshake waits).
    for (std::size_t w = 0; w < interface_words; ++w)
      words_[mbase + w] = Controller::read_data_word(interfaces_[k].number, static_cast<int>(w)).value_or(0);
    std::array<std::uint16_t, ip247_axes> pending{};
    std::array<int, ip247_axes> decode_error{};
    for (int n = 1; n <= ip247_axes; ++n) {
      const auto i = static_cast<std::size_t>(n - 1);
      const auto base = mbase + i * ip247_axis_db_words;
      pending[i] = words_[base + 4];
      if (!ready) continue;
      // BB of this cycle, before its job: the machine axis up and not in error (as in the step below).
      const std::size_t ax = machine_axis(k, n);
      m.axis(n).read_bb(ax < axes_.size() && axis(ax).status().state != motion::AxisState::error);
      std::copy_n(words_.begin() + static_cast<std::ptrdiff_t>(base), ip247_axis_db_words, block.begin());
      const Ip247Axis& a = m.axis(n);
      if (auto job = take_ip247_job(block, a.machine_data() && a.machine_data()->ag_bcd)) {
        if (*job) {
          m.command(n, **job);
        } else {
          decode_error[i] = static_cast<int>(job->error());
        }
      }
    }
    const auto job_at = static_cast<std::ptrdiff_t>(mbase + data_job_dw);
    std::vector<std::uint16_t> data_block(words_.begin() + job_at,
                                          words_.begin() + job_at + static_cast<std::ptrdiff_t>(ip247_data_job_words));
    if (ready) {
      if (const auto job = take_ip247_data_job(data_block)) {
        const auto r = m.data_job(*job, plc_);
        write_ip247_data_result(data_block, r);
        std::copy(data_block.begin(), data_block.end(), words_.begin() + job_at);
      }
    }
    for (int n = 1; n <= ip247_axes; ++n) {
      Ip247Inputs in;
      in.limit_start = io().get(in_bit(k, n, in_limit_start));
      in.limit_end = io().get(in_bit(k, n, in_limit_end));
      in.reference = io().get(in_bit(k, n, in_reference));
      in.external_stop = io().get(in_bit(k, n, in_external_stop));
      const std::size_t i = machine_axis(k, n);
      const bool bb = ready && i < axes_.size() && axis(i).status().state != motion::AxisState::error;
      in.ready = bb;
      Ip247Axis& a = m.axis(n);
      a.step(now_ns, period_ns_, in, nullptr);
      if (bb) followers_[i].step(axis(i), a, period_ns_);  // module pulse 0 = where the axis stood at power-up
      io().set(out_bit(k, n, out_in_position), a.position_reached());
      io().set(out_bit(k, n, out_moving), a.running());
      io().set(out_bit(k, n, out_error), a.error() >= 10);
    }
    for (int n = 1; n <= ip247_axes; ++n) {
      const auto i = static_cast<std::size_t>(n - 1);
      const auto base = mbase + i * ip247_axis_db_words;
      std::copy_n(words_.begin() + static_cast<std::ptrdiff_t>(base), ip247_axis_db_words, block.begin());
      const Ip247Axis& a = m.axis(n);
      write_ip247_status(block, a, a.machine_data() && a.machine_data()->ag_bcd);
      if (!ready) block[4] = pending[i];
      if (decode_error[i] != 0) block[12] = static_cast<std::uint16_t>((block[12] & 0xFF00) | decode_error[i]);
      std::copy(block.begin(), block.end(), words_.begin() + static_cast<std::ptrdiff_t>(base));
    }
    for (std::size_t w = 0; w < interface_words; ++w)
      (void)Controller::write_data_word(interfaces_[k].number, static_cast<int>(w), words_[mbase + w]);
  }
  report_errors(cycle.now);
}

std::expected<void, std::string> Ip247Controller::check_axes() {
  for (std::size_t i = 0; i < axis_count(); ++i) {
    const hil::Drive& drive = axis(i).drive();
    if (drive.capabilities().drive_profile)
      return std::unexpected(fmt::format(
          "axis '{}': its drive {} generates its own trajectory (drive profile), but the IP247 module drives its "
          "axis with its pulse train as a cyclic set-point: use a cyclic drive (stepdir `profile: motion`, CiA 402 "
          "CSP, sim)",
          axis_specs()[i].name, drive.name()));
  }
  return {};
}

std::optional<hc::DeviceErrorCode> Ip247Controller::map_axis_fault(std::size_t, const hil::Fault&,
                                                                   const motion::AxisStatus&) const noexcept {
  // A supervision fault of the machine axis (the plant did not follow the pulses) has no IP247
  // number: it stays motion:N. The module's own errors come from report_error().
  return std::nullopt;
}

void register_ip247(ControllerRegistry& registry) {
  registry.add("ip247", [](const ControllerSpec& spec) { return Ip247Controller::create(spec); });
}

}  // namespace hil::controllers::s5
