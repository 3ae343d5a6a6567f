// SPDX-License-Identifier: MIT
// Battery-buffered state of the CLM1.4 model and the error category.
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

namespace {

class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "clm14"; }
  std::string message(int code) const override { return fmt::format("CLM1.4 error {:02X}", code); }
};

}  // namespace

const std::error_category& clm_error_category() noexcept {
  static const Category c;
  return c;
}

nlohmann::json Controller::to_json() const {
  nlohmann::json j;
  nlohmann::json prog = nlohmann::json::object();
  for (int i = 0; i < program_lines; ++i)
    if (text_[static_cast<std::size_t>(i)] != "NOP")
      prog[fmt::format("{:04d}", i)] = text_[static_cast<std::size_t>(i)];
  j["program"] = prog;
  nlohmann::json logic = nlohmann::json::object();
  for (int i = 0; i < logic_lines; ++i)
    if (logic_text_[static_cast<std::size_t>(i)] != "NOP")
      logic[fmt::format("{:04d}", i)] = logic_text_[static_cast<std::size_t>(i)];
  j["logic"] = logic;
  nlohmann::json vars = nlohmann::json::object();
  for (int i = 600; i < 1000; ++i)
    if (vars_[static_cast<std::size_t>(i)] != 0)
      vars[fmt::format("{:03d}", i)] = format_variable(vars_[static_cast<std::size_t>(i)]);
  vars["019"] = format_variable(vars_[19]);
  j["variables"] = vars;
  nlohmann::json counters = nlohmann::json::object();
  for (const auto& [line, count] : counters_) counters[fmt::format("{:04d}", line)] = count;
  j["counters"] = counters;
  std::vector<int> m3, m6;
  for (std::uint8_t b = 0; b < 8; ++b) m3.push_back(image_.byte({Area::marker, 3, b}));
  for (std::uint8_t b = 0; b < 20; ++b) m6.push_back(image_.byte({Area::marker, 6, b}));
  j["markers"] = {{"M3", m3}, {"M6", m6}};
  // A program running in Automatic at the power loss can be resumed (§7.11).
  Restart r = restart_;
  if (run_ == RunState::running && mode_ == Mode::automatic && !restart_blocked_) {
    r.valid = true;
    for (std::size_t t = 0; t < 5; ++t) {
      r.pc[t] = tasks_[t].pc;
      r.phase[t] = program_[static_cast<std::size_t>(tasks_[t].pc)].op == Op::wai ? 0 : tasks_[t].phase;
      r.stack[t] = tasks_[t].stack;
      r.active[t] = tasks_[t].used && t != 2;
    }
    for (std::size_t a = 0; a < 4; ++a) {
      r.target[a] = axes_[a].target;
      r.has_target[a] = axes_[a].has_target && axes_[a].feeding;
    }
    for (std::size_t b = 0; b < 7; ++b) r.outputs[b] = image_.byte({Area::output, 1, static_cast<std::uint8_t>(b)});
  }
  if (r.valid) {
    nlohmann::json rj;
    rj["pc"] = r.pc;
    rj["phase"] = r.phase;
    rj["stack"] = r.stack;
    rj["active"] = r.active;
    rj["target"] = r.target;
    rj["has_target"] = r.has_target;
    rj["outputs"] = r.outputs;
    j["restart"] = rj;
  }
  std::array<bool, 4> sw{};
  for (std::size_t a = 0; a < 4; ++a) sw[a] = axes_[a].software_enabled;
  j["axis_enabled"] = sw;
  // The flying cutoff's length counters (status 54) run on until !CLL1 / !CLL2 [decided: kept
  // across a power loss like the other counters; the digest is silent].
  j["length_counters"] = {material_length_, product_length_};
  return j;
}

std::expected<void, std::string> Controller::from_json(const nlohmann::json& j) {
  try {
    std::vector<std::pair<int, std::string>> lines;
    if (j.contains("program"))
      for (const auto& [k, v] : j.at("program").items()) lines.emplace_back(std::stoi(k), v.get<std::string>());
    // Counters are restored after the program (storing a line applies its offset, which is +0 here).
    if (auto r = load_program(lines); !r) return std::unexpected("state: " + r.error().message);
    std::vector<std::string> logic(logic_lines, "NOP");
    logic[0] = "END";
    if (j.contains("logic")) {
      logic[0] = "NOP";
      for (const auto& [k, v] : j.at("logic").items()) {
        const int n = std::stoi(k);
        if (n < 0 || n >= logic_lines) return std::unexpected(fmt::format("state: logic line {} out of range", k));
        logic[static_cast<std::size_t>(n)] = v.get<std::string>();
      }
    }
    logic_text_ = std::move(logic);
    if (j.contains("variables"))
      for (const auto& [k, v] : j.at("variables").items()) {
        const int n = std::stoi(k);
        auto m = parse_micro(v.get<std::string>());
        if (!m || n < 0 || n >= 1000) return std::unexpected(fmt::format("state: variable {} malformed", k));
        vars_[static_cast<std::size_t>(n)] = *m;
      }
    hours_ms_ = to_double(vars_[19]) * 3.6e6;
    counters_.clear();
    if (j.contains("counters"))
      for (const auto& [k, v] : j.at("counters").items()) counters_[std::stoi(k)] = v.get<int>();
    if (j.contains("markers")) {
      const auto m3 = j.at("markers").value("M3", std::vector<int>{});
      const auto m6 = j.at("markers").value("M6", std::vector<int>{});
      for (std::size_t b = 0; b < m3.size() && b < 8; ++b)
        image_.set_byte({Area::marker, 3, static_cast<std::uint8_t>(b)}, static_cast<std::uint8_t>(m3[b]));
      for (std::size_t b = 0; b < m6.size() && b < 20; ++b)
        image_.set_byte({Area::marker, 6, static_cast<std::uint8_t>(b)}, static_cast<std::uint8_t>(m6[b]));
    }
    restart_ = Restart{};
    if (j.contains("restart")) {
      const auto& rj = j.at("restart");
      restart_.valid = true;
      restart_.pc = rj.at("pc").get<std::array<int, 5>>();
      restart_.phase = rj.value("phase", std::array<int, 5>{});
      restart_.stack = rj.at("stack").get<std::array<std::vector<int>, 5>>();
      restart_.active = rj.at("active").get<std::array<bool, 5>>();
      restart_.target = rj.at("target").get<std::array<double, 4>>();
      restart_.has_target = rj.at("has_target").get<std::array<bool, 4>>();
      restart_.outputs = rj.at("outputs").get<std::array<std::uint8_t, 7>>();
    }
    if (j.contains("axis_enabled")) {
      const auto sw = j.at("axis_enabled").get<std::array<bool, 4>>();
      for (std::size_t a = 0; a < 4; ++a) axes_[a].software_enabled = sw[a];
    }
    material_length_ = product_length_ = 0.0;
    if (j.contains("length_counters")) {
      const auto lc = j.at("length_counters").get<std::array<double, 2>>();
      if (!std::isfinite(lc[0]) || !std::isfinite(lc[1])) return std::unexpected("state: length counters malformed");
      material_length_ = lc[0];
      product_length_ = lc[1];
    }
  } catch (const std::exception& e) {
    return std::unexpected(fmt::format("state file malformed: {}", e.what()));
  }
  powered_ = false;  // the next cycle runs the power-up sequence
  return {};
}

}  // namespace hil::controllers::clm14
