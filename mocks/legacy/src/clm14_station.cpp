// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/clm14_station.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <nlohmann/json.hpp>

#include "hil/serial/clm14/serial_error.hpp"

namespace hil::mocks::legacy {

using serial::clm14::SerialError;
using serial::clm14::Telegram;

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
      axes_(std::clamp(axes, 1, 4)),
      program_(program_lines, "NOP   "),
      logic_(logic_lines, "NOP "),
      variables_(variables, "+00000000.000000") {
  logic_[0] = "END ";
  parameter_order_ = data_->parameter_numbers(axes_);
  reset_parameters();
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
  if (m == mode_) return;
  const ClmMode old = mode_;
  mode_ = m;
  if (m == ClmMode::parameter) {
    running_ = false;
    checksum_off_latched_ = !checksum_required();
  }
  if (m != ClmMode::automatic) running_ = false;
  if (old == ClmMode::parameter) {
    checksum_off_latched_ = false;
    validate_parameters();
  }
  dirty_ = true;
}

void Clm14Station::validate_parameters() {
  invalid_item_.clear();
  if (fault_ == 0x02) fault_ = 0x00;
  for (const auto& n : parameter_order_) {
    if (auto r = data_->check_parameter(n, parameter(n)); !r) {
      fault_ = 0x02;
      invalid_item_ = "0 " + n;
      return;
    }
  }
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
    out = fmt::format(":{}{:02X}\r\n", station_char_, fault_ != 0 ? fault_ : (mode_ == ClmMode::parameter ? 1 : 0));
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
  if (t.lead == '?') return reply('#', fmt::format("N{:04d} {}", n, program_[static_cast<std::size_t>(n)]));
  const std::string_view text = body.size() > 5 ? trim(body.substr(5)) : std::string_view{};
  auto checked = data_->check_program_line(text);
  if (!checked) return error(checked.error().serial_error);
  std::string stored = *checked;
  stored += stored.size() <= 3 ? "   " : " ";  // "NOP   " as the device shows an empty line
  program_[static_cast<std::size_t>(n)] = std::move(stored);
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
  if (mode_ != ClmMode::parameter) return error(code(SerialError::invalid_mode));
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
  if (t.lead == '?') return reply('V', fmt::format("{:03d} {} ", n, variables_[static_cast<std::size_t>(n)]));
  if (n < 600) return error(code(SerialError::wrong_variable_number));
  const std::string v = canonical_variable(t.body.size() > 4 ? std::string_view(t.body).substr(4) : std::string_view{});
  if (v.empty()) return error(code(SerialError::not_accepted));
  variables_[static_cast<std::size_t>(n)] = v;
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
  if (t.lead == '?') return reply('P', fmt::format("{:04d} {}", n, logic_[static_cast<std::size_t>(n)]));
  const std::string_view instr = trim(rest.substr(4));
  if (instr.empty() || instr.size() > 16) return error(code(SerialError::invalid_operand));
  logic_[static_cast<std::size_t>(n)] = std::string(instr) + " ";
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
  const int shown_fault = fault_ != 0 ? fault_ : (mode_ == ClmMode::parameter ? 0x01 : 0x00);
  std::string content;
  switch (n) {
    case 0:
    case 44:
      content = " +00000.000  +000000.000";
      break;
    case 2:
      content = "0000 0000";
      break;
    case 3:
    case 40:
      content = "00000000 00000000";
      break;
    case 5: {
      std::string fw = data_->identification().substr(0, 20);
      fw.resize(20, ' ');
      content = " " + fw;
      break;
    }
    case 8:
      content = "0000 0000 0000 0000 0000 0000";
      break;
    case 10:
    case 43:
      content = "+00000.000 +000000.000";
      break;
    case 19:
      content = data_->identification();
      break;
    case 39:
      content = "0000 0000 0000 0000";
      break;
    case 53:
      content = fmt::format("{:02X} {}", shown_fault, data_->fault_text(shown_fault));
      break;
    case 60: {
      if (arg.size() != 1 || arg[0] < '0' || arg[0] > '3') return error(code(SerialError::not_accepted));
      content = (arg[0] == '0' && !invalid_item_.empty()) ? invalid_item_ : std::string(6, ' ');
      break;
    }
    default:
      return error(code(SerialError::status_illegal));
  }
  return reply('X', fmt::format("{:02d} {} ", n, content));
}

std::string Clm14Station::on_command(const Telegram& t) {
  const std::string_view c = trim_right(t.body);
  const bool param = mode_ == ClmMode::parameter;
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
    if (mode_ != ClmMode::automatic) return error(code(SerialError::invalid_mode));
    running_ = true;
  } else if (c == "STOP") {
    running_ = false;
  } else if (c == "CLEAR") {
    if (fault_ != 0x02) fault_ = 0x00;
  } else if (c == "CSETPA") {
    if (!param) return error(code(SerialError::invalid_mode));
    reset_parameters();
  } else if (c.starts_with("CNOPNC")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 0, program_lines - 1, a, b)) return error(code(SerialError::block_number_too_large));
    for (int i = a; i <= b; ++i) program_[static_cast<std::size_t>(i)] = "NOP   ";
  } else if (c.starts_with("CNOPLT")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 0, logic_lines - 1, a, b)) return error(code(SerialError::block_number_too_large));
    for (int i = a; i <= b; ++i) logic_[static_cast<std::size_t>(i)] = "NOP ";
    if (a == 0) logic_[0] = "END ";
  } else if (c == "CCLVAR0019") {
    if (!param) return error(code(SerialError::invalid_mode));
    variables_[19] = "+00000000.000000";
  } else if (c.starts_with("CCLVAR")) {
    if (!param) return error(code(SerialError::invalid_mode));
    if (!range(c.substr(6), 600, variables - 1, a, b)) return error(code(SerialError::wrong_variable_number));
    for (int i = a; i <= b; ++i) variables_[static_cast<std::size_t>(i)] = "+00000000.000000";
  } else if (c == "CL0") {
    if (mode_ != ClmMode::manual) return error(code(SerialError::invalid_mode));
  } else if (c == "CLL1" || c == "CLL2") {
    // length counters are not modelled beyond accepting the command
  } else if (c.size() >= 4 && c[0] == 'M' && c[1] >= '1' && c[1] <= '4' &&
             (c.substr(2) == "ON" || c.substr(2) == "OFF")) {
    axis_enabled_[static_cast<std::size_t>(c[1] - '1')] = c.substr(2) == "ON";
  } else {
    return error(code(SerialError::format_error));
  }
  dirty_ = true;
  return confirm();
}

nlohmann::json Clm14Station::to_json() const {
  nlohmann::json j;
  j["station"] = station_;
  j["fault"] = fault_;
  j["invalid_item"] = invalid_item_;
  nlohmann::json prog = nlohmann::json::object();
  for (int i = 0; i < program_lines; ++i)
    if (program_[static_cast<std::size_t>(i)] != "NOP   ")
      prog[fmt::format("{:04d}", i)] = program_[static_cast<std::size_t>(i)];
  j["program"] = prog;
  nlohmann::json logic = nlohmann::json::object();
  for (int i = 0; i < logic_lines; ++i) logic[fmt::format("{:04d}", i)] = logic_[static_cast<std::size_t>(i)];
  j["logic"] = logic;
  nlohmann::json vars = nlohmann::json::object();
  for (int i = 0; i < variables; ++i)
    if (variables_[static_cast<std::size_t>(i)] != "+00000000.000000")
      vars[fmt::format("{:03d}", i)] = variables_[static_cast<std::size_t>(i)];
  j["variables"] = vars;
  j["parameters"] = parameters_;
  j["axis_enabled"] = axis_enabled_;
  return j;
}

std::expected<void, std::string> Clm14Station::from_json(const nlohmann::json& j) {
  try {
    const auto index = [](const std::string& k, int limit) -> std::expected<std::size_t, std::string> {
      if (!all_digits(k) || to_int(k) >= limit) return std::unexpected(fmt::format("bad line/variable number '{}'", k));
      return static_cast<std::size_t>(to_int(k));
    };
    std::fill(program_.begin(), program_.end(), "NOP   ");
    const nlohmann::json program_j = j.contains("program") ? j.at("program") : nlohmann::json::object();
    for (const auto& [k, v] : program_j.items()) {
      auto i = index(k, program_lines);
      if (!i) return std::unexpected("program: " + i.error());
      program_[*i] = v.get<std::string>();
    }
    const nlohmann::json logic_j = j.contains("logic") ? j.at("logic") : nlohmann::json::object();
    for (const auto& [k, v] : logic_j.items()) {
      auto i = index(k, logic_lines);
      if (!i) return std::unexpected("logic: " + i.error());
      logic_[*i] = v.get<std::string>();
    }
    const nlohmann::json variables_j = j.contains("variables") ? j.at("variables") : nlohmann::json::object();
    for (const auto& [k, v] : variables_j.items()) {
      auto i = index(k, variables);
      if (!i) return std::unexpected("variables: " + i.error());
      variables_[*i] = v.get<std::string>();
    }
    const nlohmann::json parameters_j = j.contains("parameters") ? j.at("parameters") : nlohmann::json::object();
    for (const auto& [k, v] : parameters_j.items())
      if (parameters_.contains(k)) parameters_[k] = v.get<std::string>();
    fault_ = j.value("fault", 0);
    invalid_item_ = j.value("invalid_item", std::string{});
    if (j.contains("axis_enabled")) axis_enabled_ = j["axis_enabled"].get<std::array<bool, 4>>();
  } catch (const nlohmann::json::exception& e) {
    return std::unexpected(fmt::format("state file malformed: {}", e.what()));
  }
  return {};
}

}  // namespace hil::mocks::legacy
