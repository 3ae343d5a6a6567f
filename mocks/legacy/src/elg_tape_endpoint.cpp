// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/elg_tape_endpoint.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "hil/serial/line_error.hpp"

namespace hil::mocks::legacy {

using serial::tape::ElgSectionKind;

ElgTapeEndpoint::ElgTapeEndpoint(ElgDatumCheck check, ElgEndpointOptions o)
    : check_(std::move(check)), o_(o), reader_(o.reader) {}

void ElgTapeEndpoint::raise(int alarm, std::string text) {
  alarm_ = alarm;
  alarm_text_ = std::move(text);
  reader_ = serial::tape::TapeReader(o_.reader);
  blocks_.clear();
  reading_ = false;
  deadline_ = TimePoint::max();
  dirty_ = true;
}

void ElgTapeEndpoint::set_datum(ElgSectionKind k, int number, std::string value) {
  (k == ElgSectionKind::machine_data ? md_ : sd_)[number] = std::move(value);
  dirty_ = true;
}

void ElgTapeEndpoint::finish_tape() {
  auto sections = serial::tape::parse_elg_blocks(blocks_);
  blocks_.clear();
  reader_ = serial::tape::TapeReader(o_.reader);
  reading_ = false;
  deadline_ = TimePoint::max();
  if (!sections) {
    raise(sections.error().code.value(), sections.error().message);
    return;
  }
  // Check everything first: a tape with one bad datum changes nothing.
  for (const auto& s : *sections)
    for (const auto& e : s.entries)
      if (auto why = check_ ? check_(s.kind, e.number, e.value) : std::nullopt) {
        raise(32, fmt::format("{} N{}={}: {}", serial::tape::elg_header(s.kind), e.number, e.value, *why));
        return;
      }
  for (const auto& s : *sections)
    for (const auto& e : s.entries) set_datum(s.kind, e.number, e.value);
}

std::string ElgTapeEndpoint::on_bytes(std::span<const std::uint8_t> data, TimePoint now) {
  std::string out;
  std::vector<serial::tape::TapeEvent> ev;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::uint8_t b = data[i];
    if (!reading_ && b == 0x12) {  // DC2 = remote "Data Start" in DATA OUTPUT
      out += data_start_output();
      continue;
    }
    if (!reading_ && b == 0x00) continue;  // leader feed holes between tapes
    reading_ = true;
    deadline_ = now + o_.idle_timeout;
    ev.clear();
    reader_.feed(std::span(&data[i], 1), ev);
    for (const auto& e : ev) {
      if (e.kind == serial::tape::TapeEvent::Kind::block)
        blocks_.push_back(e.text);
      else if (e.kind == serial::tape::TapeEvent::Kind::end)
        finish_tape();
      else
        raise(e.error.value(), e.message);
    }
  }
  return out;
}

std::string ElgTapeEndpoint::on_line_error(std::error_code ec, TimePoint) {
  // USART errors: 16 parity (9th bit), 17 overrun, 18 framing (manual §11).
  const int alarm = ec == serial::LineError::overrun ? 17 : ec == serial::LineError::framing ? 18 : 16;
  raise(alarm, ec.message());
  return {};
}

std::string ElgTapeEndpoint::on_idle(TimePoint now) {
  if (reading_ && now >= deadline_) raise(22, "V.24 time monitoring: no character for 60 s during a tape");
  return {};
}

std::string ElgTapeEndpoint::data_start_output() {
  serial::tape::ElgSection s;
  s.kind = next_output_sd_ ? ElgSectionKind::setting_data : ElgSectionKind::machine_data;
  for (const auto& [n, v] : next_output_sd_ ? sd_ : md_) s.entries.push_back(serial::tape::ElgEntry{n, v});
  next_output_sd_ = !next_output_sd_;
  auto tape = serial::tape::make_tape(serial::tape::make_elg_blocks(s), o_.writer);
  if (!tape) {
    raise(24, tape.error());
    return {};
  }
  return std::string(tape->begin(), tape->end());
}

std::string ElgTapeEndpoint::save_state() const {
  nlohmann::json j;
  j["device"] = "elg";
  nlohmann::json md = nlohmann::json::object(), sd = nlohmann::json::object();
  for (const auto& [n, v] : md_) md[std::to_string(n)] = v;
  for (const auto& [n, v] : sd_) sd[std::to_string(n)] = v;
  j["machine_data"] = md;
  j["setting_data"] = sd;
  j["alarm"] = alarm_;
  return j.dump(1);
}

std::expected<void, std::string> ElgTapeEndpoint::load_state(const std::string& text) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("device") || !j.at("device").is_string() ||
      j.at("device").get<std::string>() != "elg")
    return std::unexpected(std::string("not an ELG state file"));
  try {
    const nlohmann::json md = j.contains("machine_data") ? j.at("machine_data") : nlohmann::json::object();
    const nlohmann::json sd = j.contains("setting_data") ? j.at("setting_data") : nlohmann::json::object();
    for (const auto& [k, v] : md.items()) md_[std::stoi(k)] = v.get<std::string>();
    for (const auto& [k, v] : sd.items()) sd_[std::stoi(k)] = v.get<std::string>();
    alarm_ = j.value("alarm", 0);
  } catch (const std::exception& e) {
    return std::unexpected(fmt::format("ELG state file malformed: {}", e.what()));
  }
  return {};
}

}  // namespace hil::mocks::legacy
