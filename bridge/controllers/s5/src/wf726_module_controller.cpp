// SPDX-License-Identifier: MIT
// A WF 726 with several axes as one scenario controller (docs/wf725.md, "Several axes in a scenario").
#include "hil/controllers/s5/wf726_module_controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "hil/controllers/parameter_file.hpp"

namespace hil::controllers::s5 {
namespace {

constexpr std::uint32_t in_bytes = 4;                  // per axis
constexpr std::uint32_t db_bytes = 2U * wf_db::words;  // the DB axis
constexpr std::uint8_t module_supplies = 0x3F;         // input byte 3 bits 0..5: the module's checks

}  // namespace

Wf726ModuleController::Wf726ModuleController(std::shared_ptr<const profiles::Profile> profile,
                                             profiles::ParameterSet parameters,
                                             std::vector<std::unique_ptr<Wf725Controller>> axes)
    : Controller(
          std::move(profile), std::move(parameters),
          IoLayout{{in_bytes * static_cast<std::uint32_t>(axes.size()), 1U + static_cast<std::uint32_t>(axes.size()), 1,
                    db_bytes * static_cast<std::uint32_t>(axes.size())}},
          axes.front()->cycle_period()),
      axes_(std::move(axes)) {
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    auto& a = *axes_[k];
    (void)module_.add(a);  // letters checked by the factory
    a.use_user_blocks(&user_blocks_);
    auto feed = std::make_unique<Feed>();
    feed->owner = this;
    feed->k = k;
    a.io().attach(*feed);
    feeds_.push_back(std::move(feed));
    blocks_.push_back(S5DataBlock{a.interface_db().number, static_cast<std::uint32_t>(db_bytes * k), wf_db::words});
    // The axis' names on this image (the module's inputs and outputs once, by the first axis).
    for (const auto& s : a.io().signals()) {
      if (!s.bit) continue;
      (void)io().name_bit(s.name, outer(k, BitAddress{s.area, s.byte, *s.bit}));
    }
    ControllerAxis spec = a.axis_specs()[0];
    spec.limit_switches = {};  // supervised by the axis itself
    if (spec.reference && spec.reference->cam) spec.reference->cam = outer(k, *spec.reference->cam);
    add_axis(std::move(spec));
  }
}

BitAddress Wf726ModuleController::outer(std::size_t k, BitAddress a) const noexcept {
  const auto kk = static_cast<std::uint32_t>(k);
  switch (a.area) {
    case IoArea::input:
      if (a.byte == 0 || (a.byte == 3 && ((module_supplies >> a.bit) & 1U) != 0)) return a;
      return {IoArea::input, in_bytes * kk + a.byte, a.bit};
    case IoArea::output:
      return a.byte == 0 ? a : BitAddress{IoArea::output, kk + a.byte, a.bit};
    case IoArea::marker:
      return a;
    case IoArea::data:
      return {IoArea::data, db_bytes * kk + a.byte, a.bit};
  }
  return a;
}

void Wf726ModuleController::Feed::read(TimePoint, IoImage& image) noexcept {
  const IoImage& o = owner->io();
  const auto base = in_bytes * static_cast<std::uint32_t>(k);
  image.set(ByteAddress{IoArea::input, 0}, o.get(ByteAddress{IoArea::input, 0}));
  image.set(ByteAddress{IoArea::input, 1}, o.get(ByteAddress{IoArea::input, base + 1}));
  image.set(ByteAddress{IoArea::input, 2}, o.get(ByteAddress{IoArea::input, base + 2}));
  image.set(ByteAddress{IoArea::input, 3},
            static_cast<std::uint8_t>((o.get(ByteAddress{IoArea::input, 3}) & module_supplies) |
                                      (o.get(ByteAddress{IoArea::input, base + 3}) & ~module_supplies)));
  const auto d = db_bytes * static_cast<std::uint32_t>(k);
  for (std::uint32_t i = 0; i < db_bytes; ++i)
    image.set(ByteAddress{IoArea::data, i}, o.get(ByteAddress{IoArea::data, d + i}));
}

std::expected<void, std::string> Wf726ModuleController::check_axes() {
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    motion::Axis* p = &axis(k);
    if (auto r = axes_[k]->bind_axes(std::span<motion::Axis* const>(&p, 1)); !r)
      return std::unexpected(fmt::format("axis {}: {}", axes_[k]->axis_letter(), r.error()));
  }
  return {};
}

void Wf726ModuleController::on_cycle(const CycleTime& cycle) noexcept {
  std::uint8_t x7 = 0, marker = 0;
  for (std::size_t k = 0; k < axes_.size(); ++k) {
    auto& a = *axes_[k];
    (void)a.step(cycle);
    const IoImage& in = a.io();
    x7 = static_cast<std::uint8_t>(x7 | in.get(ByteAddress{IoArea::output, 0}));
    marker = static_cast<std::uint8_t>(marker | in.get(ByteAddress{IoArea::marker, 0}));
    io().set(ByteAddress{IoArea::output, 1U + static_cast<std::uint32_t>(k)}, in.get(ByteAddress{IoArea::output, 1}));
    const auto d = db_bytes * static_cast<std::uint32_t>(k);
    for (std::uint32_t i = 0; i < db_bytes; ++i)
      io().set(ByteAddress{IoArea::data, d + i}, in.get(ByteAddress{IoArea::data, i}));
    mirror_errors(k, cycle.now);
  }
  io().set(ByteAddress{IoArea::output, 0}, x7);
  io().set(ByteAddress{IoArea::marker, 0}, marker);
}

void Wf726ModuleController::mirror_errors(std::size_t k, TimePoint now) noexcept {
  const auto& a = *axes_[k];
  const int axis_index = static_cast<int>(k);
  const auto own = [&](const DeviceError& e) {
    const auto* c = catalogue(e.catalogue != nullptr ? std::string_view(e.catalogue->id()) : std::string_view{});
    return c != nullptr ? c : e.catalogue;
  };
  for (const auto& e : a.errors().active()) {
    const auto* c = own(e);
    if (c == nullptr) continue;
    const bool shown = std::any_of(errors().active().begin(), errors().active().end(), [&](const DeviceError& m) {
      return m.catalogue == c && m.code == e.code && m.axis == axis_index;
    });
    if (!shown)
      raise(*c, e.code, now, axis_index, fmt::format("axis {}", a.axis_letter()), AckRule::self_clearing, false);
  }
  std::vector<std::pair<const profiles::ErrorCatalogue*, int>> gone;
  for (const auto& m : errors().active()) {
    if (m.axis != axis_index) continue;
    const bool still = std::any_of(a.errors().active().begin(), a.errors().active().end(),
                                   [&](const DeviceError& e) { return own(e) == m.catalogue && e.code == m.code; });
    if (!still) gone.emplace_back(m.catalogue, m.code);
  }
  for (const auto& [c, code] : gone) (void)clear_error(*c, code, axis_index);
}

std::expected<BitAddress, std::string> Wf726ModuleController::resolve_bit(std::string_view text) const {
  if (auto a = io().find_bit(text)) return *a;
  if (auto s = parse_s5_address(text, blocks_.front().number); s && s->is_bit()) return to_bit_address(*s, blocks_);
  std::string dbs;
  for (const auto& b : blocks_) dbs += (dbs.empty() ? "DB" : ", DB") + std::to_string(b.number);
  return std::unexpected(fmt::format(
      "'{}' is neither an I/O name of the wf725-726 module (the axes' names: start_A, rf_B, x7_e1, ...) nor an S5 "
      "address of its DB axes ({}: 'DB11 D 2.0')",
      text, dbs));
}

std::expected<std::uint16_t, std::string> Wf726ModuleController::read_data_word(int db, int dw) const {
  for (const auto& b : blocks_)
    if (b.number == db) return Controller::read_data_word(db, dw);
  return axes_.front()->read_data_word(db, dw);  // a user data block (shared by the axes)
}

std::expected<void, std::string> Wf726ModuleController::write_data_word(int db, int dw, std::uint16_t value) {
  for (const auto& b : blocks_)
    if (b.number == db) return Controller::write_data_word(db, dw, value);
  return axes_.front()->write_data_word(db, dw, value);
}

std::expected<std::unique_ptr<Controller>, ConfigError> make_wf726_module_controller(
    const ControllerSpec& spec,
    const std::function<std::expected<std::unique_ptr<Wf725Controller>, ConfigError>(const ControllerSpec&)>&
        create_axis) {
  const auto fail = [&](std::string key, std::string message) {
    return std::unexpected(ConfigError{spec.file, spec.line, 0, "controller." + key, std::move(message)});
  };
  const auto opt = [&](std::string_view key) -> const std::string* {
    const auto it = spec.options.find(key);
    return it == spec.options.end() ? nullptr : &it->second;
  };
  const char first = opt("axis") != nullptr && opt("axis")->size() == 1 ? (*opt("axis"))[0] : 'A';
  int db = 10;
  if (const auto* v = opt("db")) {
    const auto r = std::from_chars(v->data(), v->data() + v->size(), db);
    if (r.ec != std::errc{} || r.ptr != v->data() + v->size() || db < 1 || db > 255)
      return fail("db", "db: a DB number 1..255");
  }
  struct Entry {
    char letter;
    std::filesystem::path parameters;
    int db;
  };
  std::vector<Entry> entries{{first, spec.parameters, db}};
  const auto base = std::filesystem::path(spec.file).parent_path();
  for (const char l : {'B', 'C'}) {
    const std::string key = fmt::format("axis_{}", static_cast<char>(l - 'A' + 'a'));
    const std::string dbkey = fmt::format("db_{}", static_cast<char>(l - 'A' + 'a'));
    const auto* p = opt(key);
    if (p == nullptr) {
      if (opt(dbkey) != nullptr)
        return fail(dbkey, fmt::format("{} without {}: the module has no axis {}", dbkey, key, l));
      continue;
    }
    if (l == first) return fail(key, fmt::format("axis {} is the first axis ('axis: {}', MD list 'parameters')", l, l));
    std::filesystem::path path(*p);
    if (path.is_relative() && !spec.file.empty()) path = (base / path).lexically_normal();
    int d = db + static_cast<int>(entries.size());
    if (const auto* v = opt(dbkey)) {
      const auto r = std::from_chars(v->data(), v->data() + v->size(), d);
      if (r.ec != std::errc{} || r.ptr != v->data() + v->size() || d < 1 || d > 255)
        return fail(dbkey, fmt::format("{}: the DB number 1..255 of axis {}' DB axis", dbkey, l));
    }
    for (const auto& e : entries)
      if (e.db == d)
        return fail(dbkey, fmt::format("axis {} and axis {} would both use DB{}: give {} another number", e.letter, l,
                                       d, dbkey));
    entries.push_back({l, path, d});
  }
  std::vector<std::unique_ptr<Wf725Controller>> axes;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    ControllerSpec s = spec;
    for (const char* k : {"axis_b", "axis_c", "db_b", "db_c"}) s.options.erase(k);
    s.options["axis"] = std::string(1, entries[i].letter);
    s.options["db"] = std::to_string(entries[i].db);
    s.parameters = entries[i].parameters;
    if (i > 0) s.programs.clear();  // one program memory: stored through the first axis
    auto a = create_axis(s);
    if (!a) return std::unexpected(a.error());
    if (i > 0 && (*a)->cycle_period() != axes.front()->cycle_period())
      return fail(fmt::format("axis_{}", static_cast<char>(entries[i].letter - 'A' + 'a')),
                  "the axes of one module run at one cycle: give them the same MD 38/39 (jerk limit: 8 ms)");
    axes.push_back(std::move(*a));
  }
  profiles::Settings settings;
  if (const auto* m = opt("module")) settings["module"] = *m;
  auto loaded = load_parameter_file(spec.device, spec.parameters, settings);
  if (!loaded) return std::unexpected(loaded.error());
  return std::make_unique<Wf726ModuleController>(loaded->profile, std::move(loaded->set), std::move(axes));
}

}  // namespace hil::controllers::s5
