// SPDX-License-Identifier: MIT
// The `amkasyn-sf` factory: the scenario's controller block (SF files, table DBs, AW/AZ axes,
// ID 2) into an AmkasynController. Every error names the file, the line and the key.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <optional>
#include <string_view>
#include <vector>

#include "hil/controllers/amkasyn/amkasyn_controller.hpp"
#include "hil/controllers/amkasyn/awl.hpp"
#include "hil/core/text_file.hpp"
#include "hil/profiles/loader.hpp"

namespace hil::controllers::amkasyn {
namespace {

using Unexpected = std::unexpected<ConfigError>;

std::string trim(std::string v) {
  v.erase(0, v.find_first_not_of(" \t"));
  v.erase(v.find_last_not_of(" \t") + 1);
  return v;
}

std::optional<std::int64_t> whole(const std::string& text) {
  std::int64_t n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return n;
}

/// The items of a comma-separated option value, trimmed; empty items are skipped.
std::vector<std::string> list_items(const std::string& value) {
  std::vector<std::string> items;
  std::size_t pos = 0;
  while (pos < value.size()) {
    const auto comma = value.find(',', pos);
    std::string item = trim(value.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos));
    pos = comma == std::string::npos ? value.size() : comma + 1;
    if (!item.empty()) items.push_back(std::move(item));
  }
  return items;
}

/// One "N=FILE" item of `tables:` / `fb:`, the number optionally written with its block prefix
/// ("DB16=...", "fb10=..."): the number (none unless whole) and the file (empty when missing).
struct NumberedFile {
  std::optional<std::int64_t> number;
  std::string file;
};
NumberedFile numbered_file(const std::string& item, std::string_view upper, std::string_view lower) {
  const auto eq = item.find('=');
  if (eq == std::string::npos) return {};
  std::string n = trim(item.substr(0, eq));
  if (n.starts_with(upper) || n.starts_with(lower)) n = n.substr(upper.size());
  return {whole(n), trim(item.substr(eq + 1))};
}

std::filesystem::path beside(const ControllerSpec& spec, const std::string& file) {
  std::filesystem::path p(file);
  if (p.is_absolute() || spec.file.empty()) return p;
  return (std::filesystem::path(spec.file).parent_path() / p).lexically_normal();
}

/// The catalogue-free ConfigError of a DB text.
ConfigError db_error(const std::string& file, const DbTextError& e) {
  return ConfigError{file, e.line, 0, e.item, e.message};
}

/// Line of the first "INIT <item>" (or "<item>") of an SF file, for messages.
int line_of(const std::string& text, std::string_view item) {
  int line = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    ++line;
    const auto nl = text.find('\n', pos);
    std::string l = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
    for (auto& c : l) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (const auto c = l.find_first_of(";#"); c != std::string::npos) l.resize(c);
    const auto at = l.find(item);
    if (at != std::string::npos) {
      const auto after = at + item.size();
      if (after >= l.size() || !std::isdigit(static_cast<unsigned char>(l[after]))) return line;
    }
    if (nl == std::string::npos) break;
    pos = nl + 1;
  }
  return 0;
}

struct LoadedSf {
  SfFile sf;
  std::string text;
  InitDb init;
};

std::expected<LoadedSf, ConfigError> load_sf(const std::filesystem::path& path, int id2_half_ms) {
  const std::string file = path.string();
  auto text = read_text_file(path);
  if (!text) return Unexpected(ConfigError{file, 0, 0, "", "cannot read the SF file: " + text.error()});
  // The profile engine checks the meaning: ranges, the SF type's addresses, the START rules.
  const profiles::Settings settings{{"id2_ms", static_cast<long double>(id2_half_ms) / 2.0L}};
  auto checked = load_parameter_text("amkasyn-sf", *text, file, settings);
  if (!checked) return Unexpected(checked.error());
  auto db = parse_sf_db_text(*text);
  if (!db) return Unexpected(db_error(file, db.error()));
  if (!db->has_init) {
    return Unexpected(ConfigError{file, 1, 0, "INIT DR0",
                                  "an SF file needs its FB 207 init DB (INIT DR0 = type, INIT DL0 = SF number, ...) "
                                  "besides the commanding DB"});
  }
  auto init = InitDb::parse(db->init);
  if (!init) return Unexpected(ConfigError{file, line_of(*text, "INIT DR0"), 0, "INIT", init.error().text});
  LoadedSf out{SfFile{file, std::move(*db), std::move(checked->set), std::nullopt, {}}, std::move(*text), *init};
  return out;
}

constexpr const char* known_keys =
    "device, parameters, programs, cycle, tables, start, resolution, max_rpm, aw1..aw8, awN_mode, awN_message32, "
    "awN_message16, "
    "awN_id32892, awN_id32893, az1..az4, value_new, fb";

/// The line number of an AWL parse error ("FB line N: ..."), 0 when it names none.
int awl_error_line(const std::string& error) {
  const auto at = error.find("line ");
  if (at == std::string::npos) return 0;
  int line = 0;
  const char* first = error.data() + at + 5;
  std::from_chars(first, error.data() + error.size(), line);
  return line;
}

}  // namespace

void register_amkasyn(ControllerRegistry& registry) {
  registry.add("amkasyn-sf", [](const ControllerSpec& spec) -> std::expected<std::unique_ptr<Controller>, ConfigError> {
    const auto fail = [&](std::string key, std::string message) {
      return Unexpected(ConfigError{spec.file, spec.line, 0, "controller." + key, std::move(message)});
    };
    auto profile = profiles::find_profile(spec.device);
    if (!profile) return Unexpected(profile.error());
    AmkasynSetup setup;
    // ID 2: the controller cycle, a multiple of 0.5 ms.
    const Duration cycle = spec.cycle.value_or(std::chrono::milliseconds(1));
    const Duration half = std::chrono::microseconds(500);
    if (cycle % half != Duration::zero() || cycle / half < 1 || cycle / half > 64)
      return fail("cycle", "the SF cycle is drive parameter ID 2: a multiple of 0.5 ms, 0.5 ms .. 32 ms");
    setup.id2_half_ms = static_cast<int>(cycle / half);

    std::map<std::string, std::string, std::less<>> opts(spec.options.begin(), spec.options.end());
    double max_rpm = 3000.0;
    std::array<std::string, 8> aw_axis;
    std::array<std::string, 4> az_axis;
    std::array<std::optional<AwMode>, 8> aw_mode;
    std::array<int, 8> aw_message{};
    std::array<std::int64_t, 8> aw_mul, aw_div;
    aw_mul.fill(1);
    aw_div.fill(1);
    std::vector<std::pair<int, std::string>> table_files;
    std::vector<std::string> value_new_files;
    std::vector<std::pair<int, std::string>> fb_files;
    for (const auto& [key, value] : opts) {
      const auto number = [&](std::string_view prefix, int max) -> int {
        if (!key.starts_with(prefix) || key.size() < prefix.size() + 1) return 0;
        const char c = key[prefix.size()];
        return c >= '1' && c < '1' + max ? c - '0' : 0;
      };
      if (key == "start") {
        if (value != "auto" && value != "input")
          return fail(key, "start: auto (FB 208 with each SF file's code at power-up) or input (the sfN_start bits)");
        setup.auto_start = value == "auto";
      } else if (key == "resolution") {
        const auto r = whole(value);
        if (!r || *r < 1 || *r > 1'000'000'000) return fail(key, "resolution: increments per revolution, 1..10^9");
        setup.resolution = *r;
      } else if (key == "max_rpm") {
        const auto r = whole(value);
        if (!r || *r < 1 || *r > 100000) return fail(key, "max_rpm: the drives' maximum speed in rpm, 1..100000");
        max_rpm = static_cast<double>(*r);
      } else if (key == "tables") {
        for (const auto& item : list_items(value)) {
          const auto [n, file] = numbered_file(item, "DB", "db");
          if (!n || *n < 1 || *n > 255 || file.empty())
            return fail(
                key, fmt::format("'{}': write DB=FILE, e.g. tables: \"16=db16.txt, 17=db17.txt\" (DB 1..255)", item));
          table_files.emplace_back(static_cast<int>(*n), file);
        }
      } else if (key == "fb") {
        for (const auto& item : list_items(value)) {
          const auto [n, file] = numbered_file(item, "FB", "fb");
          if (!n || *n < 0 || *n > 63 || file.empty())
            return fail(key,
                        fmt::format("'{}': write FB=FILE, e.g. fb: \"10=fb10.awl\" (the APSF's DW4, FB 0..63)", item));
          if (std::any_of(fb_files.begin(), fb_files.end(), [&](const auto& f) { return f.first == *n; }))
            return fail(key, fmt::format("FB{} is given twice", *n));
          fb_files.emplace_back(static_cast<int>(*n), file);
        }
      } else if (key == "value_new") {
        for (auto& item : list_items(value)) value_new_files.push_back(std::move(item));
      } else if (const int n = number("aw", 8); n != 0 && key.size() == 3) {
        aw_axis[static_cast<std::size_t>(n - 1)] = value;
      } else if (n != 0 && key == fmt::format("aw{}_mode", n)) {
        std::string v = value;
        for (auto& c : v) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (v == "3C0004")
          aw_mode[static_cast<std::size_t>(n - 1)] = AwMode::swq1_position;
        else if (v == "3C0404")
          aw_mode[static_cast<std::size_t>(n - 1)] = AwMode::swq2_position;
        else if (v == "3C0043")
          aw_mode[static_cast<std::size_t>(n - 1)] = AwMode::swq2_speed;
        else
          return fail(key,
                      "the drive operating mode ID 32800: 3C0004 (position, SWQ1), 3C0404 (position, SWQ2) or "
                      "3C0043 (speed, SWQ2)");
      } else if (n != 0 && key == fmt::format("aw{}_message32", n)) {
        const auto m = whole(value);
        if (!m || (*m != 0 && *m != 36 && *m != 40 && *m != 32824))
          return fail(key,
                      "ID 32786 (Config-AW message32): 0 position feedback, 36 velocity command, 40 velocity "
                      "feedback, 32824 following error");
        aw_message[static_cast<std::size_t>(n - 1)] = static_cast<int>(*m);
      } else if (n != 0 && key == fmt::format("aw{}_message16", n)) {
        // ID 32785 = 32897 (Config-AW message16 = analog input A1): the scenario gives its words.
        auto schedule = parse_analog_schedule(value);
        if (!schedule)
          return fail(key, fmt::format("the analog input A1 of AW{} (message16), raw words held from their time: {}", n,
                                       schedule.error()));
        setup.aw_message16[static_cast<std::size_t>(n - 1)] = std::move(*schedule);
      } else if (n != 0 && (key == fmt::format("aw{}_id32893", n) || key == fmt::format("aw{}_id32892", n))) {
        const bool divider = key.ends_with("32892");
        const auto v = whole(value);
        const bool ok =
            v && (divider ? (*v == 0 || (*v >= 65536 && *v <= INT32_MAX)) : (*v >= INT32_MIN && *v <= INT32_MAX));
        if (!ok)
          return fail(key, divider ? "ID 32892 (synchronous ratio divider): 0 (= 1) or 65536..2^31-1"
                                   : "ID 32893 (synchronous ratio multiplier): -2^31..2^31-1, 0 = 1");
        (divider ? aw_div : aw_mul)[static_cast<std::size_t>(n - 1)] = *v == 0 ? 1 : *v;
      } else if (const int z = number("az", 4); z != 0 && key.size() == 3) {
        az_axis[static_cast<std::size_t>(z - 1)] = value;
      } else {
        return fail(key, fmt::format("unknown controller key '{}' (known: {})", key, known_keys));
      }
    }

    // The SF files: parameters first, then programs, each one SF (init + commanding DB).
    std::vector<std::filesystem::path> files{spec.parameters};
    files.insert(files.end(), spec.programs.begin(), spec.programs.end());
    std::vector<LoadedSf> sfs;
    std::array<std::string, max_sf> by_number;
    for (const auto& f : files) {
      auto sf = load_sf(f, setup.id2_half_ms);
      if (!sf) return Unexpected(sf.error());
      auto& owner = by_number[sf->init.number];
      if (!owner.empty())
        return Unexpected(ConfigError{
            sf->sf.file, line_of(sf->text, "INIT DL0"), 0, "INIT DL0",
            fmt::format("SF{} is already initialised by {}: one file per SF number", sf->init.number, owner)});
      owner = sf->sf.file;
      sfs.push_back(std::move(*sf));
    }
    // VALUE NEW commanding DBs: DR0 names the SF; checked by the profile with that SF's init DB.
    for (const auto& file : value_new_files) {
      const auto path = beside(spec, file);
      auto text = read_text_file(path);
      if (!text) return fail("value_new", fmt::format("cannot read the VALUE NEW DB: {}", text.error()));
      auto parsed = parse_sf_db_text(*text);
      if (!parsed) return Unexpected(db_error(path.string(), parsed.error()));
      if (parsed->has_init)
        return Unexpected(ConfigError{path.string(), line_of(*text, "INIT"), 0, "INIT",
                                      "a VALUE NEW DB is a commanding DB only: the SF's init DB is in its SF file"});
      const int n = parsed->command.dr(0);
      const auto it = std::find_if(sfs.begin(), sfs.end(), [&](const LoadedSf& sf) { return sf.init.number == n; });
      if (n >= max_sf || it == sfs.end())
        return Unexpected(ConfigError{path.string(), line_of(*text, "DR0"), 0, "DR0",
                                      fmt::format("DR0 = {} names no SF of this setup", n)});
      if (it->sf.value_new)
        return fail("value_new",
                    fmt::format("SF{} has two VALUE NEW DBs ({} and {})", n, it->sf.value_new_file, path.string()));
      // The INIT lines after the file's own, so that the profile's line numbers are the file's.
      std::string combined = *text + "\n";
      std::size_t pos = 0;
      while (pos < it->text.size()) {
        const auto nl = it->text.find('\n', pos);
        const std::string line = it->text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
        pos = nl == std::string::npos ? it->text.size() : nl + 1;
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && (line.compare(first, 4, "INIT") == 0 || line.compare(first, 4, "init") == 0))
          combined += line + "\n";
      }
      const profiles::Settings settings{{"id2_ms", static_cast<long double>(setup.id2_half_ms) / 2.0L}};
      if (auto checked = load_parameter_text("amkasyn-sf", combined, path.string(), settings); !checked)
        return Unexpected(checked.error());
      it->sf.value_new = parsed->command;
      it->sf.value_new_file = path.string();
    }
    for (const auto& [db, file] : table_files) {
      const auto path = beside(spec, file);
      auto text = read_text_file(path);
      if (!text) return fail("tables", fmt::format("DB{}: cannot read the table DB: {}", db, text.error()));
      auto block = parse_table_db_text(*text);
      if (!block) return Unexpected(db_error(path.string(), block.error()));
      if (setup.tables.count(db) != 0) return fail("tables", fmt::format("DB{} is given twice", db));
      setup.tables.emplace(db, std::move(*block));
    }
    // APSF function blocks: the AWL subset (awl.hpp); a parse error names the listing's line.
    for (const auto& [fb, file] : fb_files) {
      const auto path = beside(spec, file);
      auto text = read_text_file(path);
      if (!text) return fail("fb", fmt::format("FB{}: cannot read the function block: {}", fb, text.error()));
      if (auto parsed = parse_awl(*text); !parsed) {
        const std::string& why = parsed.error();
        return Unexpected(ConfigError{path.string(), awl_error_line(why), 0, fmt::format("FB{}", fb), why});
      }
      setup.fbs.emplace_back(fb, std::move(*text));
    }
    // Every table DB an init DB names must exist (the DFKT output table Tab7 is created: the SF writes it).
    for (const auto& sf : sfs)
      for (std::size_t k = 0; k < 8; ++k) {
        const int db = sf.init.tables[k];
        if (db == 0 || setup.tables.count(db) != 0) continue;
        if (sf.init.type == SfType::dfkt && k == 7) {
          setup.tables.emplace(db, DataBlock(6));
          continue;
        }
        const std::string item = fmt::format("INIT {}{}", k % 2 == 0 ? "DR" : "DL", 6 + k / 2);
        return Unexpected(ConfigError{sf.sf.file, line_of(sf.text, item), 0, item,
                                      fmt::format("Tab{} = DB{}, but the scenario gives no table DB{}: add it to "
                                                  "the controller's tables: \"{}=FILE\"",
                                                  k, db, db, db)});
      }

    // Axes: AW1..AW8, then the AZ masters, each machine axis once.
    std::vector<std::string> names;
    const auto axis_index = [&](const std::string& name) {
      const auto it = std::find(names.begin(), names.end(), name);
      if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
      names.push_back(name);
      return names.size() - 1;
    };
    for (std::size_t k = 0; k < 8; ++k) {
      if (aw_axis[k].empty()) {
        if (aw_mode[k] || aw_message[k] != 0 || aw_mul[k] != 1 || aw_div[k] != 1 || !setup.aw_message16[k].empty())
          return fail(fmt::format("aw{}", k + 1),
                      fmt::format("aw{}_... configure a drive: name its axis, aw{}: NAME", k + 1, k + 1));
        continue;
      }
      AwChannel ch;
      ch.axis = axis_index(aw_axis[k]);
      ch.message32 = aw_message[k];
      ch.ratio_mul = aw_mul[k];
      ch.ratio_div = aw_div[k];
      std::optional<AwMode> from_sink;
      for (const auto& sf : sfs)
        if (sf.init.sink.address == k + 1)
          from_sink = sf.init.sink.offset == 4 ? AwMode::swq1_position : AwMode::swq2_position;
      ch.mode = aw_mode[k].value_or(from_sink.value_or(AwMode::swq1_position));
      if (from_sink && (*from_sink == AwMode::swq1_position) != (ch.mode == AwMode::swq1_position))
        return fail(fmt::format("aw{}_mode", k + 1),
                    fmt::format("an SF writes AW{} {} but ID 32800 selects {}: 3C0004 takes SWQ1 (sink offset 4), "
                                "3C0404 / 3C0043 take SWQ2 (sink offset 16)",
                                k + 1, *from_sink == AwMode::swq1_position ? "SWQ1" : "SWQ2",
                                ch.mode == AwMode::swq1_position ? "SWQ1" : "SWQ2"));
      if (ch.mode != AwMode::swq1_position && (ch.ratio_mul != 1 || ch.ratio_div != 1))
        return fail(fmt::format("aw{}_id32893", k + 1),
                    fmt::format("the synchronous ratio ID 32892/32893 acts on SWQ1 only (ID 32800 = 3C0004); AW{} "
                                "runs on SWQ2",
                                k + 1));
      setup.aw[k] = ch;
    }
    for (std::size_t k = 0; k < 4; ++k) {
      bool high = false, wide = false;
      for (const auto& sf : sfs)
        if (sf.init.source.address == 0 && sf.init.source.offset != 0) {
          const bool w = sf.init.source.offset >= 16;
          const std::size_t msg = w ? (sf.init.source.offset - 16u) / 2u : (sf.init.source.offset - 1u) / 2u;
          if (msg != k) continue;
          (w ? wide : high) = true;
          if (az_axis[k].empty())
            return Unexpected(ConfigError{sf.sf.file, line_of(sf.text, "INIT DR2"), 0, "INIT DR2",
                                          fmt::format("SF{} reads the AZ message {}: name the axis its pulse-generator "
                                                      "input counts with the controller key az{}: NAME",
                                                      sf.init.number, k + 1, k + 1)});
        }
      if (high && wide)
        return fail(
            fmt::format("az{}", k + 1),
            fmt::format("AZ message {} is read both as a 16-bit high word and as 32 bits: use one form", k + 1));
      if (!az_axis[k].empty()) setup.az[k] = AzChannel{axis_index(az_axis[k]), high};
    }
    for (const auto& sf : sfs)
      for (const auto& [h, what, item] :
           {std::tuple{sf.init.source, "reads", "INIT DL2"}, std::tuple{sf.init.sink, "writes", "INIT DL3"}})
        if (h.address >= 1 && h.address <= 8 && !setup.aw[h.address - 1u])
          return Unexpected(ConfigError{sf.sf.file, line_of(sf.text, item), 0, item,
                                        fmt::format("SF{} {} AW{}: map the drive onto a machine axis with the "
                                                    "controller key aw{}: NAME",
                                                    sf.init.number, what, h.address, h.address)});

    std::vector<ControllerAxis> axes;
    const double velocity = max_rpm * static_cast<double>(setup.resolution) / 60.0;
    for (const auto& name : names) {
      ControllerAxis a;
      a.name = name;
      a.units = "inc";
      auto& c = a.config;
      c.name = name;
      c.inc_per_unit = motion::Ratio{1, 1};
      // [decision] The SF data define no drive dynamics: max_rpm, a 0.1 s ramp without jerk limit, one revolution
      // of following error, in position = on the increment (docs/amkasyn.md).
      c.limits = {velocity, velocity * 10.0};  // trapezoidal: the drives have no jerk parameter here
      c.quick_stop_deceleration = velocity * 20.0;
      c.jog_velocity = velocity / 10.0;
      c.following_error.static_window = static_cast<double>(setup.resolution);
      c.standstill_window = 2.0;
      c.in_position_window = 0.5;
      c.in_position_timeout = std::chrono::seconds(2);
      if (auto v = motion::validate(c); !v) return fail("aw", v.error());
      axes.push_back(std::move(a));
    }
    for (auto& sf : sfs) setup.sfs.push_back(std::move(sf.sf));
    auto controller = std::make_unique<AmkasynController>(*profile, std::move(setup), std::move(axes));
    // FB 207 of every file must have been accepted (InitDb::parse succeeded above; the runtime
    // refuses nothing else at init).
    return controller;
  });
}

}  // namespace hil::controllers::amkasyn
