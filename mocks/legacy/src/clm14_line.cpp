// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/clm14_line.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "hil/serial/clm14/serial_error.hpp"

namespace hil::mocks::legacy {

Clm14Line::Clm14Line(std::shared_ptr<const serial::clm14::DeviceData> data, int stations, int axes) {
  if (stations <= 0) {
    stations_.push_back(std::make_unique<Clm14Station>(0, data, axes));
  } else {
    for (int s = 1; s <= std::min(stations, 32); ++s)
      stations_.push_back(std::make_unique<Clm14Station>(s, data, axes));
  }
}

void Clm14Line::answer(const Clm14Station& station, std::string bytes, TimePoint now, std::string& out) {
  if (bytes.empty()) return;
  const Duration delay = station.response_delay();
  if (delay == Duration::zero() && held_.empty()) {
    out += bytes;
    return;
  }
  TimePoint due = now + delay;
  if (!held_.empty() && held_.back().due > due) due = held_.back().due;  // never overtakes an earlier answer
  held_.push_back(Held{due, std::move(bytes)});
}

std::string Clm14Line::on_idle(TimePoint now) {
  for (auto& s : stations_) s->tick(now);
  std::string out;
  while (!held_.empty() && held_.front().due <= now) {
    out += held_.front().bytes;
    held_.pop_front();
  }
  return out;
}

TimePoint Clm14Line::next_deadline() const {
  TimePoint t = held_.empty() ? TimePoint::max() : held_.front().due;
  for (const auto& s : stations_) t = std::min(t, s->ticking() ? s->next_cycle() : TimePoint{});  // {}: start now
  return t;
}

std::string Clm14Line::on_bytes(std::span<const std::uint8_t> data, TimePoint now) {
  // The controllers run up to now first, so a status reply shows the present state.
  for (auto& s : stations_)
    if (s->ticking()) s->tick(now);
  std::string out;
  for (std::uint8_t b : data) {
    const auto ev = splitter_.feed(static_cast<char>(b));
    if (ev == serial::clm14::LineSplitter::Event::overflow) {
      line_corrupt_ = true;  // answered when its LF arrives
      continue;
    }
    if (ev != serial::clm14::LineSplitter::Event::line) continue;
    std::string line = splitter_.take_line();
    ++lines_;
    if (line_corrupt_) {
      line_corrupt_ = false;
      for (auto& s : stations_) answer(*s, s->on_damaged_line(line), now, out);
      continue;
    }
    for (auto& s : stations_) answer(*s, s->on_line(line), now, out);
  }
  return out;
}

std::string Clm14Line::on_line_error(std::error_code, TimePoint) {
  line_corrupt_ = true;
  return {};
}

bool Clm14Line::take_dirty() {
  bool any = false;
  for (auto& s : stations_) any = s->take_dirty() || any;
  return any;
}

std::string Clm14Line::save_state() const {
  nlohmann::json j;
  j["device"] = "clm14";
  j["format"] = 1;
  j["stations"] = nlohmann::json::array();
  for (const auto& s : stations_) j["stations"].push_back(s->to_json());
  return j.dump(1);
}

std::expected<void, std::string> Clm14Line::load_state(const std::string& text) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::unexpected(std::string("state file is not valid JSON"));
  if (!j.contains("device") || !j.at("device").is_string() || j.at("device").get<std::string>() != "clm14")
    return std::unexpected(std::string("state file is not a clm14 state"));
  if (j.contains("stations") && !j.at("stations").is_array())
    return std::unexpected(std::string("state file malformed: 'stations' is not a list"));
  try {
    const nlohmann::json st = j.value("stations", nlohmann::json::array());
    for (std::size_t i = 0; i < st.size() && i < stations_.size(); ++i) {
      if (auto r = stations_[i]->from_json(st[i]); !r)
        return std::unexpected(fmt::format("station {}: {}", i + 1, r.error()));
    }
  } catch (const std::exception& e) {  // a value of the wrong type deep inside a station
    return std::unexpected(fmt::format("state file malformed: {}", e.what()));
  }
  return {};
}

void Clm14Line::set_mode(ClmMode m) {
  for (auto& s : stations_) s->set_mode(m);
}

}  // namespace hil::mocks::legacy
