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
#include "hil/controllers/s5/ip247_interface.hpp"
#include "hil/controllers/s5/ip247_program.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"
#include "hil/profiles/loader.hpp"
#include "hil/serial/s5/db_listing.hpp"

namespace hil::controllers::s5 {

namespace {

namespace hc = hil::controllers;

constexpr hc::BitAddress in_limit_start{hc::IoArea::input, 0, 0};
constexpr hc::BitAddress in_limit_end{hc::IoArea::input, 0, 1};
constexpr hc::BitAddress in_reference{hc::IoArea::input, 0, 2};
constexpr hc::BitAddress in_external_stop{hc::IoArea::input, 0, 3};
constexpr hc::BitAddress out_in_position{hc::IoArea::output, 0, 0};
constexpr hc::BitAddress out_moving{hc::IoArea::output, 0, 1};
constexpr hc::BitAddress out_error{hc::IoArea::output, 0, 2};

/// The interface DB lies at the start of the data area (20 words = 40 bytes).
constexpr std::uint32_t interface_bytes = 2 * ip247_axis_db_words;

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
    if (k != "axis" && k != "interface_db" && k != "sysid_module")
      return std::unexpected(ConfigError{
          spec.file, spec.line, 0, "controller." + k,
          fmt::format("unknown key '{}' of the ip247 controller (allowed: device, parameters, programs, cycle, axis, "
                      "interface_db, sysid_module)",
                      k)});
  }
  auto profile = profiles::find_profile("ip247");
  if (!profile) return std::unexpected(profile.error());
  auto interface_db = option_int(spec, "interface_db", 1, 255, 10);
  if (!interface_db) return std::unexpected(interface_db.error());
  auto sysid = option_int(spec, "sysid_module", 0, 255, 0);
  if (!sysid) return std::unexpected(sysid.error());

  // The MD DB: a STEP 5 DB listing with one 70-word image.
  auto text = read_text(spec.parameters, spec, "parameters");
  if (!text) return std::unexpected(text.error());
  auto dbs = serial::s5::parse_db_listing(*text, spec.parameters.string());
  if (!dbs) return std::unexpected(listing_error(dbs.error(), spec.parameters, "controller.parameters"));
  const auto md_it = std::find_if(dbs->begin(), dbs->end(),
                                  [](const serial::s5::DbImage& d) { return d.words.size() == ip247_md_words; });
  if (md_it == dbs->end())
    return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                       "no 70-word IP247 machine-data DB in the listing (DW0 = KF +00070)"});
  auto md = parse_ip247_md_db(md_it->words);
  if (!md)
    return std::unexpected(ConfigError{
        spec.parameters.string(), 0, 0, "controller.parameters",
        fmt::format("IP247 MD error {}: {}", static_cast<int>(md.error()), make_error_code(md.error()).message())});
  if (*interface_db == md_it->db)
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.interface_db",
                                       fmt::format("DB{} is the machine-data DB: give the interface DB another "
                                                   "number",
                                                   *interface_db)});

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
      if (f.number == *interface_db || f.number == md_it->db)
        return std::unexpected(
            ConfigError{file.string(), 1, 1, "program",
                        fmt::format("program {} would be DB{}, which is the {} DB: use another program number",
                                    f.number, f.number, f.number == *interface_db ? "interface" : "machine-data")});
      if (!numbers.insert(f.number).second)
        return std::unexpected(
            ConfigError{file.string(), 1, 1, "program",
                        fmt::format("program {} is given twice (error 49: no overwrite)", f.number)});
      programs.push_back(std::move(f));
    }
  }

  const Duration cycle = spec.cycle.value_or(std::chrono::milliseconds(2));
  auto c = std::make_unique<Ip247Controller>(*profile, *md, md_it->db, *interface_db, std::move(programs), cycle);
  const auto e = c->axis_.load_machine_data(*md, *sysid);
  if (e != stepdir::Ip247MdError::none)
    return std::unexpected(
        ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                    fmt::format("IP247 MD error {}: {}", static_cast<int>(e), make_error_code(e).message())});
  c->md_ = *c->axis_.machine_data();
  c->write_programs();
  c->publish_status();

  // The machine axis: the motor behind the module's pulse output, 1 increment = 1 pulse.
  hc::ControllerAxis a;
  a.name = spec.options.contains("axis") ? spec.options.find("axis")->second : std::to_string(md->axis);
  const std::int64_t bu_per_unit = md->unit == Ip247Unit::inch ? 10'000 : 1'000;
  a.units = md->unit == Ip247Unit::inch ? "inch" : md->unit == Ip247Unit::degree ? "deg" : "mm";
  auto& cfg = a.config;
  cfg.name = a.name;
  const std::int64_t num = std::int64_t{md->pulses_per_rev} * bu_per_unit;
  const std::int64_t g = std::gcd(num, std::int64_t{md->gear_bu_per_rev});
  cfg.inc_per_unit = {num / g, md->gear_bu_per_rev / g};
  const double ipu = static_cast<double>(num) / static_cast<double>(md->gear_bu_per_rev);
  cfg.limits.velocity = static_cast<double>(md->fmax_hz) / ipu;
  cfg.limits.acceleration = static_cast<double>(md->accel_mhz_per_ms) / ipu;  // mHz/ms = Hz/s
  cfg.quick_stop_deceleration = cfg.limits.acceleration;
  cfg.jog_velocity = std::min(cfg.limits.velocity, static_cast<double>(md->jog1) / 60.0);
  if (md->rotary) {
    cfg.rotary = true;
    cfg.modulo = static_cast<double>(md->sw_end - md->sw_start) / static_cast<double>(bu_per_unit);
  }
  // The module supervises its own limits (SW limits 28/29, limit switches 25/26) and plans the
  // motion; the motion core only follows and guards the plant (50 ms of travel at vmax).
  const double pulse = 1.0 / ipu;
  cfg.following_error.static_window = std::max(0.05 * cfg.limits.velocity, 10.0 * pulse);
  cfg.standstill_window = std::max(2.0 * pulse, 1e-9);
  cfg.in_position_window = pulse;
  cfg.reaction = motion::FaultReaction::stop;
  a.warnings.push_back(
      "the IP247 module plans the motion (its exponential ramp, the programmed speeds) and supervises software limits, "
      "limit switches, backlash and offsets itself; the machine axis follows its pulses from its own zero");
  if (const auto v = motion::validate(cfg); !v)
    return std::unexpected(ConfigError{spec.parameters.string(), 0, 0, "controller.parameters",
                                       "the machine data give an axis the motion core rejects: " + v.error()});
  const std::string& n = a.name;
  auto& io = c->io();
  for (const auto& [name, bit] : {std::pair{"limit_minus_" + n, in_limit_start},
                                  {"limit_plus_" + n, in_limit_end},
                                  {"reference_cam_" + n, in_reference},
                                  {"external_stop_" + n, in_external_stop},
                                  {"in_position_" + n, out_in_position},
                                  {"moving_" + n, out_moving},
                                  {"error_" + n, out_error}}) {
    if (auto r = io.name_bit(name, bit); !r)
      return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller.axis", r.error()});
  }
  c->add_axis(std::move(a));
  return std::unique_ptr<hc::Controller>(std::move(c));
}

Ip247Controller::Ip247Controller(std::shared_ptr<const profiles::Profile> profile, const Ip247MachineData& md,
                                 int md_db, int interface_db, std::vector<Ip247ProgramFile> programs, Duration cycle)
    : hc::Controller(std::move(profile), profiles::ParameterSet{}, hc::IoLayout{{1, 1, 1, interface_bytes}}, cycle),
      md_(md),
      md_db_(md_db),
      interface_{static_cast<std::uint16_t>(interface_db), 0, static_cast<std::uint16_t>(ip247_axis_db_words)},
      program_files_(std::move(programs)),
      axis_(store_, md.axis),
      kin_(ip247_kinematics(md)) {
  words_.assign(ip247_axis_db_words, 0);
  publish_status();
}

void Ip247Controller::publish_status() noexcept {
  write_ip247_status(words_, axis_, md_.ag_bcd);
  for (std::size_t w = 0; w < words_.size(); ++w)
    (void)Controller::write_data_word(interface_.number, static_cast<int>(w), words_[w]);
}

std::expected<hc::BitAddress, std::string> Ip247Controller::resolve_bit(std::string_view text) const {
  if (auto named = hc::Controller::resolve_bit(text)) return named;
  auto a = hc::parse_s5_address(text, interface_.number);
  if (!a) return std::unexpected(a.error());
  return hc::to_bit_address(*a, data_blocks());
}

std::expected<std::uint16_t, std::string> Ip247Controller::read_data_word(int db, int dw) const {
  if (db == interface_.number) return Controller::read_data_word(db, dw);
  const std::vector<std::uint16_t>* image = nullptr;
  std::vector<std::uint16_t> md_image;
  if (db == md_db_) {
    md_image = make_ip247_md_db(md_);
    image = &md_image;
  } else if (const auto it = vp_images_.find(db); it != vp_images_.end()) {
    image = &it->second;
  }
  if (image == nullptr) {
    std::string list = fmt::format("DB{} (interface), DB{} (machine data)", interface_.number, md_db_);
    for (const auto& [n, w] : vp_images_) list += fmt::format(", DB{} (program {})", n, n);
    return std::unexpected(fmt::format("the ip247 module has no DB{} (it has {})", db, list));
  }
  if (dw < 0 || static_cast<std::size_t>(dw) >= image->size())
    return std::unexpected(
        fmt::format("DB{} of the ip247 module has data words 0..{}; DW {} is beyond it", db, image->size() - 1, dw));
  return (*image)[static_cast<std::size_t>(dw)];
}

std::expected<void, std::string> Ip247Controller::write_data_word(int db, int dw, std::uint16_t value) {
  if (db != interface_.number)
    return std::unexpected(fmt::format(
        "DB{} of the ip247 module is not written word by word: the PLC writes the interface DB{} (the MD and "
        "VP DBs are images the module checks as a whole, given in 'parameters:' and 'programs:')",
        db, interface_.number));
  return Controller::write_data_word(db, dw, value);
}

std::vector<std::string> Ip247Controller::trace_signals() const {
  return {"actual_value_BU", "error_number", "m_output"};
}

double Ip247Controller::trace_value(std::size_t i) const noexcept {
  switch (i) {
    case 0:
      return static_cast<double>(axis_.actual());
    case 1:
      return axis_.error();
    case 2:
      return axis_.m_output();
    default:
      return 0.0;
  }
}

void Ip247Controller::write_programs() {
  for (const auto& f : program_files_) {
    Ip247SyntaxFault fault;
    const auto e = store_.write(f.number, f.text, &fault);
    auto image = make_ip247_vp_db(Ip247VpImage{static_cast<std::uint8_t>(f.number), f.text, 0, 0});
    std::vector<std::uint16_t> words = image ? std::move(*image) : std::vector<std::uint16_t>{};
    if (e == stepdir::Ip247Error::program_faulty && !words.empty()) set_ip247_vp_error(words, fault);
    if (!words.empty()) vp_images_[f.number] = std::move(words);
    if (e == stepdir::Ip247Error::none) continue;
    refused_.push_back(
        {static_cast<int>(e),
         e == stepdir::Ip247Error::program_faulty
             ? fmt::format("program {} ({}): syntax error {} in block N{}: {}", f.number, f.file.string(),
                           static_cast<int>(fault.code), fault.block_number, fault.message)
             : fmt::format("program {} ({}) not stored", f.number, f.file.string())});
  }
}

void Ip247Controller::report_error(TimePoint now) noexcept {
  const int e = axis_.error() >= 10 ? axis_.error() : 0;
  if (e == shown_error_) return;
  if (const auto* cat = catalogue("module")) {
    if (shown_error_ != 0) (void)clear_error(*cat, shown_error_, 0);
    if (e != 0)
      raise(*cat, e, now, 0,
            fmt::format("axis {}, BA {}, actual value {} BU", axis_specs()[0].name, axis_.ba(), axis_.actual()),
            hc::AckRule::self_clearing, false);
  }
  shown_error_ = e;
}

void Ip247Controller::on_cycle(const CycleTime& cycle) noexcept {
  const std::int64_t now_ns = cycle.now.time_since_epoch().count();
  period_ns_ = cycle_period().count();
  // BB: the power section is the machine axis; the module enables it at power-up.
  const bool ready = power_up_axes();
  const auto state = axis(0).status().state;
  const bool bb = ready && state != motion::AxisState::error;
  if (!started_) {
    // The VP DBs the PLC wrote at start that the module refused (error 48 ...).
    if (const auto* cat = catalogue("module"))
      for (const auto& [code, context] : refused_) raise(*cat, code, cycle.now, 0, context, std::nullopt, false);
    started_ = true;
  }
  // The PLC's job: BA, parameters and a command bit in the interface DB. Until the power section
  // is up at power-on the module takes no job (DW4 stays set: the PLC's handshake waits).
  for (std::size_t w = 0; w < words_.size(); ++w)
    words_[w] = Controller::read_data_word(interface_.number, static_cast<int>(w)).value_or(0);
  const std::uint16_t pending = words_[4];
  int decode_error = 0;
  if (ready) {
    if (auto job = take_ip247_job(words_, md_.ag_bcd)) {
      if (*job) {
        axis_.command(**job);
      } else {
        decode_error = static_cast<int>(job->error());
      }
    }
  }
  Ip247Inputs in;
  in.limit_start = io().get(in_limit_start);
  in.limit_end = io().get(in_limit_end);
  in.reference = io().get(in_reference);
  in.external_stop = io().get(in_external_stop);
  in.ready = bb;
  axis_.step(now_ns, period_ns_, in, nullptr);
  if (bb) follower_.step(axis(0), axis_, period_ns_);  // module pulse 0 = where the axis stood at power-up
  write_ip247_status(words_, axis_, md_.ag_bcd);
  if (!ready) words_[4] = pending;
  if (decode_error != 0) words_[12] = static_cast<std::uint16_t>((words_[12] & 0xFF00) | decode_error);
  for (std::size_t w = 0; w < words_.size(); ++w)
    (void)Controller::write_data_word(interface_.number, static_cast<int>(w), words_[w]);
  io().set(out_in_position, axis_.position_reached());
  io().set(out_moving, axis_.running());
  io().set(out_error, axis_.error() >= 10);
  report_error(cycle.now);
}

std::expected<void, std::string> Ip247Controller::check_axes() {
  const hil::Drive& drive = axis(0).drive();
  if (drive.capabilities().drive_profile)
    return std::unexpected(fmt::format(
        "axis '{}': its drive {} generates its own trajectory (drive profile), but the IP247 module drives its axis "
        "with its pulse train as a cyclic set-point: use a cyclic drive (stepdir `profile: motion`, CiA 402 CSP, "
        "sim)",
        axis_specs()[0].name, drive.name()));
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
