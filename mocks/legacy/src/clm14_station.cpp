// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/clm14_station.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <optional>

#include "hil/serial/clm14/serial_error.hpp"

namespace hil::mocks::legacy {

using serial::clm14::SerialError;
using serial::clm14::Telegram;
namespace cc = controllers::clm14;

namespace {

std::string_view trim_right(std::string_view s) {
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}
std::string_view trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  return trim_right(s);
}
bool all_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}
int to_int(std::string_view s) {
  int v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}
constexpr int code(SerialError e) {
  return static_cast<int>(e);
}

/// "+12345678.123456" canonical form of a variable value, or empty when malformed.
std::string canonical_variable(std::string_view v) {
  v = trim(v);
  if (v.empty()) return {};
  char sign = '+';
  if (v.front() == '+' || v.front() == '-') {
    sign = v.front();
    v.remove_prefix(1);
  }
  const auto dot = v.find_first_of(".,");
  const std::string_view ip = v.substr(0, dot);
  const std::string_view fp = dot == std::string_view::npos ? std::string_view{} : v.substr(dot + 1);
  if (ip.empty() || ip.size() > 8 || !all_digits(ip) || fp.size() > 6 || (!fp.empty() && !all_digits(fp))) return {};
  std::string out(1, sign);
  out += std::string(8 - ip.size(), '0');
  out += ip;
  out += '.';
  out += fp;
  out += std::string(6 - fp.size(), '0');
  return out;
}

}  // namespace

Clm14Station::Clm14Station(int station, std::shared_ptr<const serial::clm14::DeviceData> data, int axes)
    : station_(station),
      station_char_(serial::clm14::station_char(station).value_or(' ')),
      data_(std::move(data)),
      axes_(std::clamp(axes, 1, 4)) {
  parameter_order_ = data_->parameter_numbers(axes_);
  reset_parameters();
  clm_.set_parameters([this](std::string_view n) { return parameter(n); });
  clm_.set_parameter_validator([this]() -> std::expected<void, cc::ProgramError> {
    for (const auto& n : parameter_order_)
      if (auto r = data_->check_parameter(n, parameter(n)); !r)
        return std::unexpected(cc::ProgramError{cc::ClmError::parameter_invalid, -1, n + ": " + r.error().message});
    return {};
  });
  clm_.on_settings([this](const cc::Settings& s) {
    if (!external_axes_) sim_.rebuild(s);
    attach_axes();
    auto* before = wheel_.port();
    wheel_.rebuild(s);
    if (wheel_.port() != before && external_me_[0] == nullptr) clm_.attach_master_encoder(wheel_.port());
  });
  // The wiring of a unit on the bench: E-Stop and Immediate Stop closed, axis enables on.
  auto& im = clm_.image();
  im.set_bit(cc::sys::emergency_stop_ok, true);
  im.set_bit(cc::sys::immediate_stop_ok, true);
  for (const auto& e : cc::sys::enable) im.set_bit(e, true);
}

void Clm14Station::attach_axes() {
  for (int ax = 1; ax <= 4; ++ax)
    clm_.attach_axis(ax, external_axes_ ? external_ports_[static_cast<std::size_t>(ax - 1)] : sim_.port(ax));
}

void Clm14Station::use_master_encoder(int n, cc::MasterEncoderPort* port) {
  if (n == 1) {
    external_me_[0] = port;
    clm_.attach_master_encoder(port != nullptr ? port : wheel_.port());
  } else if (n == 2) {
    external_me_[1] = port;
    clm_.attach_master_encoder2(port);
  }
}

void Clm14Station::use_axes(std::array<cc::AxisPort*, 4> ports, std::function<void(const CycleTime&)> update) {
  external_axes_ = true;
  external_ports_ = ports;
  external_update_ = std::move(update);
  sim_ = Clm14SimAxes{};
  attach_axes();
}

void Clm14Station::cycle(TimePoint now) {
  clm_.cycle(now);
  const CycleTime c{now, clm_.cycle_time()};
  wheel_.update(c);
  if (external_axes_) {
    if (external_update_) external_update_(c);
  } else {
    sim_.update(c);
  }
}

void Clm14Station::tick(TimePoint now) {
  if (!started_) {
    started_ = true;
    next_cycle_ = now;
    last_save_ = now;
  }
  for (int n = 0; next_cycle_ <= now && n < 5000; ++n) {
    cycle(next_cycle_);
    next_cycle_ += clm_.cycle_time();
  }
  if (next_cycle_ <= now) next_cycle_ = now + clm_.cycle_time();  // too far behind: skip, do not replay
  // A running program changes counters and variables all the time: persist about once a second.
  // The console's hardware settings are saved at once; the length counters, which the material
  // moves in Manual too, like a running program.
  const std::array<int, 5> hw{clm_.analog_input(1), clm_.analog_input(2), clm_.analog_input(3), clm_.analog_input(4),
                              clm_.test_speed_step()};
  if (hw != saved_hardware_) {
    saved_hardware_ = hw;
    dirty_ = true;
  }
  const std::array<double, 2> lengths{clm_.length_counter(1), clm_.length_counter(2)};
  if ((clm_.run_state() == cc::RunState::running || lengths != saved_lengths_) &&
      now - last_save_ >= std::chrono::seconds(1)) {
    last_save_ = now;
    saved_lengths_ = lengths;
    dirty_ = true;
  }
}

ClmMode Clm14Station::mode() const noexcept {
  switch (clm_.mode()) {
    case cc::Mode::parameter:
      return ClmMode::parameter;
    case cc::Mode::automatic:
      return ClmMode::automatic;
    case cc::Mode::manual:
      break;
  }
  return ClmMode::manual;
}

std::string Clm14Station::program_line(int n) const {
  std::string t = clm_.line_text(n);
  t += t.size() <= 3 ? "  " : " ";  // "MNE data " / "NOP  ": §9.2 "#5N0123 NOP  $45"
  return t;
}

void Clm14Station::reset_parameters() {
  parameters_.clear();
  for (const auto& n : parameter_order_) parameters_[n] = data_->parameter_default(n);
  if (station_ > 0) {
    // An RS-485 station talks on X8 (B004/B005): same format as X6, its station number,
    // and confirmations on so the master can pace its writes.
    parameters_["B004"] = parameters_["B002"];
    parameters_["B005"] = fmt::format("0 1 {:02d} 0 000 000", station_);
  }
  dirty_ = true;
}

std::string Clm14Station::parameter(std::string_view number) const {
  const auto it = parameters_.find(number);
  return it == parameters_.end() ? std::string{} : it->second;
}

bool Clm14Station::checksum_required() const {
  if (checksum_off_latched_) return false;
  const std::string f = parameter(station_ > 0 ? "B005" : "B003");
  return f.empty() || f[0] == '0' || f[0] == '2';
}

bool Clm14Station::confirmation_on() const {
  const std::string f = parameter(station_ > 0 ? "B005" : "B003");
  return f.size() >= 3 && f[2] == '1';
}

hil::Duration Clm14Station::response_delay() const {
  if (station_ == 0) return Duration::zero();
  const std::string f = parameter("B005");
  // Fields separated by single spaces: H C NN E DDD RRR; DDD starts at offset 9.
  if (f.size() < 12 || f[8] != ' ') return Duration::zero();
  int ms = 0;
  for (std::size_t i = 9; i < 12; ++i) {
    if (f[i] < '0' || f[i] > '9') return Duration::zero();
    ms = ms * 10 + (f[i] - '0');
  }
  return std::chrono::milliseconds(ms);
}

std::string Clm14Station::reply(char lead, std::string_view body) const {
  return serial::clm14::make_telegram(lead, station_char_, body, true);
}

std::string Clm14Station::error(int c) const {
  return reply('X', serial::clm14::make_error_body(c, data_->serial_error_text(c)));
}

std::string Clm14Station::confirm() const {
  return confirmation_on() ? std::string("Y\r\n") : std::string{};
}

void Clm14Station::set_mode(ClmMode m) {
  const ClmMode old = mode();
  if (m == ClmMode::parameter && old != ClmMode::parameter) checksum_off_latched_ = !checksum_required();
  if (old == ClmMode::parameter && m != ClmMode::parameter) checksum_off_latched_ = false;
  auto& im = clm_.image();
  im.set_bit(cc::sys::parameter_mode, m == ClmMode::parameter);
  im.set_bit(cc::sys::automatic, m == ClmMode::automatic);
  // The mode switch acts at once: run the next cycle now (a ticking unit runs it a little early).
  if (!started_) {
    cycle(clm_.powered() ? clm_.now() + clm_.cycle_time() : clm_.now());
  } else {
    cycle(next_cycle_);
    next_cycle_ += clm_.cycle_time();
  }
  dirty_ = true;
}

std::string Clm14Station::on_damaged_line(std::string_view line) {
  if (line.size() >= 2 && station_ > 0 && line[1] != station_char_) return {};
  return error(code(SerialError::format_error));
}

std::string Clm14Station::on_line(std::string_view line) {
  if (line.empty()) return {};
  bool addressed = true;
  bool broadcast = false;
  if (line.size() >= 2 && line != "Y") {
    const char s = line[1];
    if (station_ == 0) {
      if (s != ' ') return error(code(SerialError::format_error));
    } else if (s == ' ') {
      broadcast = true;
    } else if (s != station_char_) {
      addressed = false;
    }
  }
  if (!addressed) return {};  // another station's telegram: silent
  // '!' commands always need the checksum; the RS-485 poll ":s" never carries one.
  const bool command = line[0] == '!';
  const bool poll = line[0] == ':';
  auto parsed = serial::clm14::parse_telegram(line, !poll && (command || checksum_required()));
  if (!parsed) return broadcast ? std::string{} : error(static_cast<int>(parsed.error().code));
  const Telegram& t = *parsed;
  std::string out;
  if (t.lead == ':') {
    out = fmt::format(":{}{:02X}\r\n", station_char_, fault() != 0 ? fault() : (mode() == ClmMode::parameter ? 1 : 0));
  } else if (t.lead == '!' && !t.body.empty() && t.body[0] == 'K') {
    out = on_parameter(t);
  } else if (t.lead == '!') {
    out = on_command(t);
  } else if (t.lead == '?' || t.lead == '#') {
    const char kind = t.body.empty() ? '\0' : t.body[0];
    switch (kind) {
      case 'N':
        out = on_program(t);
        break;
      case 'K':
        out = on_parameter(t);
        break;
      case 'V':
        out = on_variable(t);
        break;
      case 'P':
        out = on_logic(t);
        break;
      case 'X':
        out = t.lead == '?' ? on_status(t) : error(code(SerialError::format_error));
        break;
      default:
        out = error(code(SerialError::format_error));
    }
  } else {
    out = error(code(SerialError::format_error));
  }
  return broadcast ? std::string{} : out;
}

std::string Clm14Station::on_program(const Telegram& t) {
  const std::string_view body = t.body;
  const std::string_view num = body.substr(1, 4);
  if (num.size() != 4 || !all_digits(num)) return error(code(SerialError::block_number_wrong));
  const int n = to_int(num);
  if (n >= program_lines) return error(code(SerialError::block_number_too_large));
  if (t.lead == '?') return reply('#', fmt::format("N{:04d} {}", n, program_line(n)));
  const std::string_view text = body.size() > 5 ? trim(body.substr(5)) : std::string_view{};
  auto checked = data_->check_program_line(text);
  if (!checked) return error(checked.error().serial_error);
  // The controller checks the operands (axis, I/O, line numbers); a line it cannot run is
  // "RS Block Data Error" and nothing is stored.
  if (auto r = clm_.store_line(n, *checked); !r) return error(code(SerialError::block_data_error));
  dirty_ = true;
  return confirm();
}

std::string Clm14Station::on_parameter(const Telegram& t) {
  // "K B002 019200 0 1 8 1" (one space after K; the number is block xx + item yy)
  std::string_view rest = std::string_view(t.body).substr(1);
  if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  if (rest.size() < 4) return error(code(SerialError::format_error));
  const std::string_view block = rest.substr(0, 2);
  const std::string_view item = rest.substr(2, 2);
  const bool block_ok =
      block == "B0" || block == "C0" || (block[0] == 'A' && block[1] >= '1' && block[1] <= '0' + axes_);
  if (!block_ok) return error(code(SerialError::invalid_param_block));
  if (!all_digits(item)) return error(code(SerialError::wrong_param_number));
  const std::string number(rest.substr(0, 4));
  const auto it = parameters_.find(number);
  if (it == parameters_.end()) return error(code(SerialError::param_number_too_large));
  if (t.lead == '?') return reply('#', fmt::format("K {} {}", number, it->second));
  if (mode() != ClmMode::parameter) return error(code(SerialError::invalid_mode));
  std::string_view data = rest.size() > 4 ? rest.substr(4) : std::string_view{};
  if (!data.empty() && data.front() == ' ') data.remove_prefix(1);
  it->second = std::string(trim_right(data));
  dirty_ = true;
  return confirm();
}

std::string Clm14Station::on_variable(const Telegram& t) {
  const std::string_view num = std::string_view(t.body).substr(1, 3);
  if (num.size() != 3 || !all_digits(num)) return error(code(SerialError::wrong_variable_number));
  const int n = to_int(num);
  if (t.lead == '?') return reply('V', fmt::format("{:03d} {} ", n, cc::format_variable(clm_.variable(n))));
  if (n < 600) return error(code(SerialError::wrong_variable_number));
  const std::string v = canonical_variable(t.body.size() > 4 ? std::string_view(t.body).substr(4) : std::string_view{});
  const auto m = cc::parse_micro(v);
  if (v.empty() || !m || !clm_.set_variable(n, *m)) return error(code(SerialError::not_accepted));
  dirty_ = true;
  return confirm();
}

std::string Clm14Station::on_logic(const Telegram& t) {
  std::string_view rest = std::string_view(t.body).substr(1);
  if (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  const std::string_view num = rest.substr(0, 4);
  if (num.size() != 4 || !all_digits(num)) return error(code(SerialError::block_number_wrong));
  const int n = to_int(num);
  if (n >= logic_lines) return error(code(SerialError::block_number_too_large));
  if (t.lead == '?') return reply('P', fmt::format("{:04d} {} ", n, clm_.logic_line(n)));
  const std::string_view instr = trim(rest.substr(4));
  if (instr.empty() || instr.size() > 16) return error(code(SerialError::invalid_operand));
  // The operand is checked like the device does: by compiling the line on its own.
  const std::string line(instr);
  if (line != "END" && line != "NOP" && line != ")") {
    if (auto p = cc::LogicProgram::compile({line, "END"}); !p) {
      const auto par = cc::LogicProgram::compile({line, ")", "END"});  // an opening "AND(" alone is fine
      if (!par) return error(code(SerialError::invalid_operand));
    }
  }
  clm_.store_logic_line(n, line);
  dirty_ = true;
  return confirm();
}

std::string Clm14Station::on_status(const Telegram& t) {
  std::string_view rest = std::string_view(t.body).substr(1);
  while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
  const std::string_view num = rest.substr(0, 2);
  if (num.size() != 2 || !all_digits(num)) return error(code(SerialError::wrong_status_number));
  const int n = to_int(num);
  const std::string_view arg = rest.size() > 2 ? trim(rest.substr(2)) : std::string_view{};
  bool ok = true;
  int err = 0;
  const std::string content = status_content(n, arg, ok, err);
  if (!ok) return error(err);
  return reply('X', fmt::format("{:02d} {} ", n, content));
}

std::string Clm14Station::on_command(const Telegram& t) {
  const std::string_view c = trim_right(t.body);
  const bool param = mode() == ClmMode::parameter;
  const auto range = [&](std::string_view tail, int lo, int hi, int& a, int& b) {
    if (tail.empty()) {
      a = lo;
      b = hi;
      return true;
    }
    if (tail.size() != 8 || !all_digits(tail)) return false;
    a = to_int(tail.substr(0, 4));
    b = to_int(tail.substr(4, 4));
    return a >= lo && b <= hi && a <= b;
  };
  int a = 0, b = 0;
  if (c == "START") {
    if (!clm_.command_start()) return error(code(SerialError::invalid_mode));
  } else if (c == "STOP") {
    clm_.command_stop();
  } else if (c == "CLEAR") {
    clm_.command_clear();
  } else if (c == "CSETPA") {
    if (!param) return error(code(SerialError::invalid_mode));
    reset_parameters();
  } else if (c.starts_with("CNOPNC")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 0, program_lines - 1, a, b)) return error(code(SerialError::block_number_too_large));
    for (int i = a; i <= b; ++i) (void)clm_.store_line(i, "NOP");
  } else if (c.starts_with("CNOPLT")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 0, logic_lines - 1, a, b)) return error(code(SerialError::block_number_too_large));
    for (int i = a; i <= b; ++i) clm_.store_logic_line(i, "NOP");
    if (a == 0) clm_.store_logic_line(0, "END");
  } else if (c == "CCLVAR0019") {
    if (!param) return error(code(SerialError::invalid_mode));
    clm_.clear_hour_counter();
  } else if (c.starts_with("CCLVAR")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 600, variables - 1, a, b)) return error(code(SerialError::wrong_variable_number));
    for (int i = a; i <= b; ++i) (void)clm_.set_variable(i, 0);
  } else if (c == "CL0") {
    if (mode() != ClmMode::manual) return error(code(SerialError::invalid_mode));
    (void)clm_.command_start_0000();  // flying cutoff: the next Automatic starts at 0000 (A138)
  } else if (c == "CLL1" || c == "CLL2") {
    clm_.clear_length_counter(c[3] - '0');  // flying cutoff: material / product length counter (status 54)
  } else if (c.size() >= 4 && c[0] == 'M' && c[1] >= '1' && c[1] <= '4' &&
             (c.substr(2) == "ON" || c.substr(2) == "OFF")) {
    clm_.set_axis_software_enable(c[1] - '0', c.substr(2) == "ON");
  } else {
    return error(code(SerialError::format_error));
  }
  dirty_ = true;
  return confirm();
}

nlohmann::json Clm14Station::to_json() const {
  nlohmann::json j;
  j["station"] = station_;
  j["parameters"] = parameters_;
  j["controller"] = clm_.to_json();
  j["hardware"] = {{"analog_mv", std::array<int, 4>{clm_.analog_input(1), clm_.analog_input(2), clm_.analog_input(3),
                                                    clm_.analog_input(4)}},
                   {"test_speed_step", clm_.test_speed_step()}};
  return j;
}

std::expected<void, std::string> Clm14Station::from_json(const nlohmann::json& j) {
  try {
    const nlohmann::json parameters_j = j.contains("parameters") ? j.at("parameters") : nlohmann::json::object();
    for (const auto& [k, v] : parameters_j.items())
      if (parameters_.contains(k)) parameters_[k] = v.get<std::string>();
    nlohmann::json c;
    if (j.contains("controller")) {
      c = j.at("controller");
    } else {
      // State files written before the controller model: program/logic/variables per station.
      c["program"] = nlohmann::json::object();
      if (j.contains("program"))
        for (const auto& [k, v] : j.at("program").items()) c["program"][k] = std::string(trim(v.get<std::string>()));
      c["logic"] = nlohmann::json::object();
      if (j.contains("logic"))
        for (const auto& [k, v] : j.at("logic").items()) c["logic"][k] = std::string(trim(v.get<std::string>()));
      c["variables"] = j.contains("variables") ? j.at("variables") : nlohmann::json::object();
      if (j.contains("axis_enabled")) c["axis_enabled"] = j.at("axis_enabled");
    }
    const nlohmann::json program_j = c.contains("program") ? c.at("program") : nlohmann::json::object();
    for (const auto& [k, v] : program_j.items())
      if (!all_digits(k) || to_int(k) >= program_lines)
        return std::unexpected(fmt::format("program: bad line number '{}'", k));
    if (auto r = clm_.from_json(c); !r) return std::unexpected(r.error());
    if (j.contains("hardware")) {
      const auto& h = j.at("hardware");
      // Whole numbers only (a float outside int would not convert): bad values are errors.
      const auto whole = [](const nlohmann::json& v, std::int64_t lo, std::int64_t hi) -> std::optional<int> {
        if (!v.is_number_integer()) return std::nullopt;
        const auto x = v.get<std::int64_t>();
        if (x < lo || x > hi) return std::nullopt;
        return static_cast<int>(x);
      };
      if (h.contains("analog_mv")) {
        const auto& mv = h.at("analog_mv");
        if (!mv.is_array() || mv.size() != 4)
          return std::unexpected("hardware: analog_mv needs 4 values (AE1..AE4, mV)");
        for (std::size_t i = 0; i < 4; ++i) {
          const auto v = whole(mv[i], -10000, 10000);
          if (!v)
            return std::unexpected(
                fmt::format("hardware: analog input AE{} {} outside ±10000 mV", i + 1, mv[i].dump()));
          clm_.set_analog_input(static_cast<int>(i) + 1, *v);
        }
      }
      if (h.contains("test_speed_step")) {
        const auto step = whole(h.at("test_speed_step"), 0, cc::Controller::test_speed_steps - 1);
        if (!step)
          return std::unexpected(
              fmt::format("hardware: test speed step {} outside 0..31", h.at("test_speed_step").dump()));
        clm_.set_test_speed_step(*step);
      }
    }
    saved_hardware_ = {clm_.analog_input(1), clm_.analog_input(2), clm_.analog_input(3), clm_.analog_input(4),
                       clm_.test_speed_step()};
    saved_lengths_ = {clm_.length_counter(1), clm_.length_counter(2)};
  } catch (const nlohmann::json::exception& e) {
    return std::unexpected(fmt::format("state file malformed: {}", e.what()));
  }
  return {};
}

}  // namespace hil::mocks::legacy
