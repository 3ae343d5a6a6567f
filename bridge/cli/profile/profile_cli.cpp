// SPDX-License-Identifier: MIT
// `hilbridge profile list|show|validate|encode|decode`: the device profiles of profiles/devices.
#include <fmt/format.h>

#include <fstream>
#include <optional>
#include <sstream>

#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/core/text_file.hpp"
#include "hil/profiles/loader.hpp"
#include "hil/profiles/parameter_set.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"
#include "profile_cli.hpp"

namespace hil::cli {
namespace {

namespace hp = hil::profiles;

struct Options {
  std::string device;
  std::string param;
  std::string value;
  std::string file;
  std::string errors;
  bool show_errors = false;
  bool partial = false;
  bool json = false;  ///< one JSON object on stdout (docs/json.md)
  std::vector<std::string> sets;
};

/// "error: ..." on stderr, and {"error": ...} on stdout under --json; sets `exit_code`.
void failed(const Options& o, int& exit_code, const std::string& what, int code,
            nlohmann::json extra = nlohmann::json::object()) {
  exit_code = report_error(o.json, "error: ", what, code, std::move(extra));
}

/// A Problem as JSON (validate, and the field checks of encode/decode).
nlohmann::json problem_json(const hp::Problem& pr, std::string_view file) {
  return {{"line", pr.line == 0 ? nlohmann::json(nullptr) : nlohmann::json(pr.line)},
          {"param", pr.param},
          {"field", pr.field},
          {"value", pr.value},
          {"rule", pr.rule},
          {"message", pr.message},
          {"text", pr.describe(file)}};
}

/// The fields of a value with their names and units (encode/decode --json).
nlohmann::json value_json(const hp::ParamVariant& v, const hp::ParamValue& value) {
  nlohmann::json fields = nlohmann::json::array();
  for (std::size_t i = 0; i < v.fields.size() && i < value.size(); ++i)
    fields.push_back({{"name", v.fields[i].name}, {"value", hp::to_string(value[i])}, {"unit", v.fields[i].unit}});
  return fields;
}

std::expected<hp::Settings, std::string> parse_settings(const hp::Profile& p, const std::vector<std::string>& sets) {
  hp::Settings s;
  for (const auto& kv : sets) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) return std::unexpected(fmt::format("--set '{}': expected name=value", kv));
    const std::string name = kv.substr(0, eq), value = kv.substr(eq + 1);
    if (!p.setting(name)) {
      std::string known;
      for (const auto& x : p.settings) known += (known.empty() ? "" : ", ") + x.name;
      return std::unexpected(fmt::format("--set {}: {} has no such setting (settings: {})", name, p.device,
                                         known.empty() ? "none" : known));
    }
    if (auto d = hp::parse_decimal(value))
      s[name] = d->to_long_double();
    else
      s[name] = value;
  }
  return s;
}

std::shared_ptr<const hp::Profile> load(const Options& o, int& exit_code) {
  auto p = hp::find_profile(o.device);
  if (!p) {
    std::string names;
    for (const auto& n : hp::list_profiles()) names += (names.empty() ? "" : ", ") + n;
    fmt::print(stderr, "known devices: {}\n", names.empty() ? "none (set HILBRIDGE_PROFILES)" : names);
    failed(o, exit_code, p.error().describe(), 2, {{"known_devices", hp::list_profiles()}});
    return nullptr;
  }
  return *p;
}

/// Resolves PARAM and its variant for the given settings; prints the reason on failure.
const hp::ParamVariant* variant_for(const Options& o, const hp::Profile& p, const hp::Settings& s, hp::ParamRef& ref,
                                    int& exit_code) {
  auto r = p.resolve(o.param);
  if (!r) {
    failed(o, exit_code,
           fmt::format("{} has no parameter '{}' (see: hilbridge profile show {})", p.device, o.param, p.device), 2);
    return nullptr;
  }
  ref = *r;
  hp::ParameterSet empty;
  const hp::Scope scope(p, &empty, s);
  const auto* v = hp::select_variant(ref, scope);
  if (!v) {
    std::string conds;
    for (const auto& x : ref.spec->variants) conds += (conds.empty() ? "" : " | ") + x.when.text();
    failed(o, exit_code,
           fmt::format("{} does not exist for this configuration; it applies when {} (choose with --set)", ref.id(),
                       conds),
           2);
    return nullptr;
  }
  return v;
}

/// The value's field problems (range, step, rules of one field); printed unless `json`.
std::vector<hp::Problem> field_problems(const hp::ParamRef& ref, const hp::ParamVariant& v, const hp::ParamValue& value,
                                        const hp::Profile& p, const hp::Settings& s, bool json, int& exit_code) {
  hp::ParameterSet empty;
  const hp::Scope scope(p, &empty, s);
  std::vector<hp::Problem> out;
  for (std::size_t i = 0; i < v.fields.size() && i < value.size(); ++i)
    for (auto& pr : hp::check_field(ref, v.fields[i], value[i], scope)) {
      if (!json) fmt::print("error: {}\n", pr.describe());
      exit_code = 1;
      out.push_back(std::move(pr));
    }
  return out;
}

std::string units(const hp::ParamVariant& v) {
  std::string u;
  for (const auto& f : v.fields)
    if (!f.unit.empty()) u += (u.empty() ? "" : ", ") + f.unit;
  return u.empty() ? "" : " [" + u + "]";
}

void run_list(Context& ctx) {
  const auto names = hp::list_profiles();
  if (names.empty()) {
    fmt::print(stderr, "error: no profiles found; searched:");
    for (const auto& d : hp::profile_search_path()) fmt::print(stderr, " {}", d.string());
    fmt::print(stderr, "\nset HILBRIDGE_PROFILES to the folder holding <device>.yaml\n");
    ctx.exit_code = 2;
    return;
  }
  fmt::print("{:<16} {:>10} {:>8}  {}\n", "DEVICE", "PARAMETERS", "ERRORS", "TITLE");
  for (const auto& n : names) {
    auto p = hp::find_profile(n);
    if (!p) {
      fmt::print("{:<16} error: {}\n", n, p.error().describe());
      ctx.exit_code = 1;
      continue;
    }
    std::size_t codes = 0;
    for (const auto& c : (*p)->catalogues) codes += c->entries().size();
    fmt::print("{:<16} {:>10} {:>8}  {}\n", n, (*p)->all_refs().size(), codes, (*p)->title);
  }
}

void run_show(Context& ctx, const Options& o) {
  auto p = load(o, ctx.exit_code);
  if (!p) return;
  if (o.show_errors) {
    if (!o.errors.empty() && !p->catalogue(o.errors))
      return failed(o, ctx.exit_code, fmt::format("{} has no error catalogue '{}'", p->device, o.errors), 2);
    if (o.json)
      print_json(profile::catalogues_json(*p, o.errors));
    else
      profile::print_catalogues(*p, o.errors);
    return;
  }
  if (o.param.empty()) {
    if (o.json)
      print_json(profile::overview_json(*p));
    else
      profile::print_overview(*p);
    return;
  }
  auto ref = p->resolve(o.param);
  if (!ref && o.json) {
    auto codes = profile::error_codes_json(*p, o.param);
    if (codes.empty())
      return failed(o, ctx.exit_code, fmt::format("{} has no parameter or error code '{}'", p->device, o.param), 2);
    print_json({{"device", p->device}, {"error_codes", std::move(codes)}});
    return;
  }
  if (!ref) {
    // an error code of one or more catalogues?
    bool found = false;
    for (const auto& c : p->catalogues)
      if (auto code = c->parse_code(o.param); code && c->find(*code)) {
        const auto* e = c->find(*code);
        fmt::print("{} {} ({}): {}{}\n  cause: {}\n  remedy: {}\n  reaction: {}; acknowledge: {}\n", c->id(),
                   e->code_text, c->category().name(), e->text, e->text_de.empty() ? "" : " [" + e->text_de + "]",
                   e->cause, e->remedy, hp::to_string(e->reaction), e->acknowledge);
        found = true;
      }
    if (found) return;
    fmt::print(stderr, "error: {} has no parameter or error code '{}'\n", p->device, o.param);
    ctx.exit_code = 2;
    return;
  }
  if (o.json)
    print_json(profile::parameter_json(*p, *ref));
  else
    profile::print_parameter(*p, *ref);
}

void run_validate(Context& ctx, const Options& o) {
  auto p = load(o, ctx.exit_code);
  if (!p) return;
  auto settings = parse_settings(*p, o.sets);
  if (!settings) return failed(o, ctx.exit_code, settings.error(), 2);
  auto buf = read_text_file(o.file);
  if (!buf) return failed(o, ctx.exit_code, fmt::format("cannot read the parameter set: {}", buf.error()), 2);
  auto parser = hp::make_parameter_set_parser(p);
  if (!parser)
    return failed(o, ctx.exit_code,
                  fmt::format("{} declares the unknown parameter-set format '{}'", p->device, p->text_format), 2);
  const auto parsed = parser->parse(*buf, *settings);
  auto problems = parsed.problems;
  for (auto& pr : hp::validate(*p, parsed.set, *settings)) {
    if (o.partial && pr.rule.starts_with("required")) continue;
    problems.push_back(std::move(pr));
  }
  std::stable_sort(problems.begin(), problems.end(), [](const hp::Problem& a, const hp::Problem& b) {
    if ((a.line == 0) != (b.line == 0)) return a.line != 0;
    return a.line < b.line;
  });
  if (o.json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& pr : problems) list.push_back(problem_json(pr, o.file));
    print_json({{"device", p->device},
                {"file", o.file},
                {"valid", problems.empty()},
                {"parameters", parsed.set.entries.size()},
                {"problems", std::move(list)}});
    if (!problems.empty()) ctx.exit_code = 1;
    return;
  }
  for (const auto& pr : problems) fmt::print("{}\n", pr.describe(o.file));
  if (problems.empty()) {
    fmt::print("{}: valid {} parameter set ({} parameters)\n", o.file, p->device, parsed.set.entries.size());
  } else {
    fmt::print("{}: {} problem(s) in a {} parameter set of {} parameters\n", o.file, problems.size(), p->device,
               parsed.set.entries.size());
    ctx.exit_code = 1;
  }
}

/// What encode and decode both start from: the profile, the `--set` settings and the
/// parameter's variant under them. Reports the problem and sets `exit_code` when one is missing.
struct ParamTarget {
  std::shared_ptr<const hp::Profile> profile;
  hp::Settings settings;
  hp::ParamRef ref;
  const hp::ParamVariant* variant = nullptr;
};

std::optional<ParamTarget> resolve_param(const Options& o, int& exit_code) {
  ParamTarget t;
  t.profile = load(o, exit_code);
  if (!t.profile) return std::nullopt;
  auto settings = parse_settings(*t.profile, o.sets);
  if (!settings) {
    failed(o, exit_code, settings.error(), 2);
    return std::nullopt;
  }
  t.settings = std::move(*settings);
  t.variant = variant_for(o, *t.profile, t.settings, t.ref, exit_code);
  if (!t.variant) return std::nullopt;
  return t;
}

void run_encode(Context& ctx, const Options& o) {
  auto t = resolve_param(o, ctx.exit_code);
  if (!t) return;
  const auto& p = t->profile;
  const auto& settings = t->settings;
  const auto& ref = t->ref;
  const auto* v = t->variant;
  auto value = hp::parse_value_input(*v, o.value);
  if (!value) return failed(o, ctx.exit_code, fmt::format("{} = '{}': {}", ref.id(), o.value, value.error()), 1);
  auto img = hp::encode_value(*p, *v, *value);
  if (!img) return failed(o, ctx.exit_code, fmt::format("{} = {}: {}", ref.id(), o.value, img.error()), 1);
  if (o.json) {
    nlohmann::json j{{"device", p->device},
                     {"param", ref.id()},
                     {"name", v->name},
                     {"value", hp::value_text(*v, *value)},
                     {"fields", value_json(*v, *value)},
                     {"wire",
                      {{"text", img->text},
                       {"words", img->words},
                       {"bcd", img->bcd ? nlohmann::json(fmt::format("{:08X}", *img->bcd)) : nullptr},
                       {"binary", img->binary ? nlohmann::json(fmt::format("{:08X}", *img->binary)) : nullptr}}},
                     {"device_text", nullptr}};
    if (auto parser = hp::make_parameter_set_parser(p)) {
      hp::ParameterSet one;
      one.device = p->device;
      one.set({ref, *value, 0, hp::value_text(*v, *value)});
      j["device_text"] = parser->write(one, settings);
    }
    nlohmann::json problems = nlohmann::json::array();
    for (const auto& pr : field_problems(ref, *v, *value, *p, settings, true, ctx.exit_code))
      problems.push_back(problem_json(pr, {}));
    j["problems"] = std::move(problems);
    print_json(j);
    return;
  }
  fmt::print("{} {} = {}{}\n", ref.id(), v->name, hp::value_text(*v, *value), units(*v));
  fmt::print("{}", img->describe());
  // the parameter as a line of the device's own text format
  if (auto parser = hp::make_parameter_set_parser(p)) {
    hp::ParameterSet one;
    one.device = p->device;
    one.set({ref, *value, 0, hp::value_text(*v, *value)});
    fmt::print("device text:\n{}", parser->write(one, settings));
  }
  (void)field_problems(ref, *v, *value, *p, settings, false, ctx.exit_code);
}

void run_decode(Context& ctx, const Options& o) {
  auto t = resolve_param(o, ctx.exit_code);
  if (!t) return;
  const auto& p = t->profile;
  const auto& settings = t->settings;
  const auto& ref = t->ref;
  const auto* v = t->variant;
  auto value = hp::decode_wire(*p, *v, o.value);
  if (!value) return failed(o, ctx.exit_code, fmt::format("{} wire '{}': {}", ref.id(), o.value, value.error()), 1);
  if (o.json) {
    nlohmann::json fields = value_json(*v, *value);
    for (std::size_t i = 0; i < v->fields.size() && i < fields.size(); ++i) {
      const auto& f = v->fields[i];
      const auto* d = std::get_if<hp::Decimal>(&(*value)[i]);
      if (d && f.type == hp::FieldType::bits)
        if (auto b = hp::parse_bit_field(static_cast<std::uint64_t>(d->units), f.bits))
          fields[i]["meaning"] = hp::bit_field_text(*b, f.bits);
      if (d && f.type == hp::FieldType::choice)
        for (const auto& c : f.choices)
          if (hp::Decimal{c.value, 0} == *d) fields[i]["meaning"] = c.meaning;
    }
    nlohmann::json problems = nlohmann::json::array();
    for (const auto& pr : field_problems(ref, *v, *value, *p, settings, true, ctx.exit_code))
      problems.push_back(problem_json(pr, {}));
    print_json({{"device", p->device},
                {"param", ref.id()},
                {"name", v->name},
                {"wire", o.value},
                {"value", hp::value_text(*v, *value)},
                {"fields", std::move(fields)},
                {"problems", std::move(problems)}});
    return;
  }
  fmt::print("{} {} = {}{}\n", ref.id(), v->name, hp::value_text(*v, *value), units(*v));
  for (std::size_t i = 0; i < v->fields.size(); ++i) {
    const auto& f = v->fields[i];
    if (f.type == hp::FieldType::bits)
      if (const auto* d = std::get_if<hp::Decimal>(&(*value)[i]))
        if (auto b = hp::parse_bit_field(static_cast<std::uint64_t>(d->units), f.bits))
          fmt::print("  {}: {}\n", f.name, hp::bit_field_text(*b, f.bits));
    if (f.type == hp::FieldType::choice)
      if (const auto* d = std::get_if<hp::Decimal>(&(*value)[i]))
        for (const auto& c : f.choices)
          if (hp::Decimal{c.value, 0} == *d) fmt::print("  {}: {}\n", f.name, c.meaning);
  }
  (void)field_problems(ref, *v, *value, *p, settings, false, ctx.exit_code);
}

}  // namespace

void register_profile(Context& ctx) {
  auto opts = std::make_shared<Options>();
  auto* cmd = ctx.app.add_subcommand(
      "profile",
      "Device profiles of the legacy controllers (CLM1.4, SINUMERIK ELG, IP247, WF 725/726, AMKASYN SF):\n"
      "parameters, value codecs, validation of parameter sets and error catalogues.\n"
      "Profiles are YAML files found in $HILBRIDGE_PROFILES, <exe>/../profiles/devices or the source tree.");
  cmd->require_subcommand(1);

  auto* list = cmd->add_subcommand("list", "List the device profiles found, with parameter and error-code counts");
  list->callback([&ctx] { run_list(ctx); });

  auto* show = cmd->add_subcommand(
      "show", "Show a profile, one parameter (every variant, field, range, default, rule) or an error catalogue");
  show->add_option("device", opts->device, "Device name, e.g. clm14, wf725-726, ip247, sinumerik-elg, amkasyn-sf")
      ->required();
  show->add_option("param", opts->param,
                   "Parameter id (A106, MD11, DW5, fmax, MD396*) or an error code of a catalogue");
  show->add_flag("--errors", opts->show_errors, "List the error catalogues (all, or the one named by --catalogue)");
  show->add_option("--catalogue", opts->errors,
                   "Error catalogue to list with --errors (e.g. diagnostic, serial, traversing)");
  show->add_flag("--json", opts->json, "One JSON object on stdout (docs/json.md); errors as {\"error\": ...} too");
  show->callback([&ctx, opts] { run_show(ctx, *opts); });

  auto* validate = cmd->add_subcommand(
      "validate",
      "Validate a parameter set in the device's own text format; every problem is listed with its line.\n"
      "Exit code 0 = valid, 1 = problems found, 2 = usage error.");
  validate->add_option("device", opts->device, "Device name")->required();
  validate
      ->add_option(
          "file", opts->file,
          "Parameter set file (CLM K telegrams, WF 'MD n = v', IP247 S5 DB listing, ELG %TEA1/%SEA tape, AMK DB lines)")
      ->required();
  validate->add_option("--set", opts->sets,
                       "Setting name=value (e.g. module=WF726C, hardware_axes=2, id2_ms=2); repeatable");
  validate->add_flag("--partial", opts->partial, "Do not report parameters missing from the set");
  validate->add_flag("--json", opts->json, "One JSON object on stdout (docs/json.md); errors as {\"error\": ...} too");
  validate->callback([&ctx, opts] { run_validate(ctx, *opts); });

  auto* encode = cmd->add_subcommand(
      "encode", "Print a value's wire form (telegram field text, BCD and binary words, data words, tape block)");
  encode->add_option("device", opts->device, "Device name")->required();
  encode->add_option("param", opts->param, "Parameter id")->required();
  encode
      ->add_option("value", opts->value,
                   "Value in the parameter's unit; several fields space-separated in one argument (\"3000 10\"); after "
                   "-- for negative values")
      ->required();
  encode->add_option(
      "--set", opts->sets,
      "Setting name=value selecting the variant (e.g. control=AK, resolution=10, sf_type=6); repeatable");
  encode->add_flag("--json", opts->json, "One JSON object on stdout (docs/json.md); errors as {\"error\": ...} too");
  encode->callback([&ctx, opts] { run_encode(ctx, *opts); });

  auto* decode = cmd->add_subcommand(
      "decode",
      "Decode a wire form back to the value (\"03000 10.0\", \"8002 4537\", \"HEX FFFF A027\", \"0000 1388\")");
  decode->add_option("device", opts->device, "Device name")->required();
  decode->add_option("param", opts->param, "Parameter id")->required();
  decode->add_option("wire", opts->value, "Wire form as printed by encode")->required();
  decode->add_option("--set", opts->sets, "Setting name=value selecting the variant; repeatable");
  decode->add_flag("--json", opts->json, "One JSON object on stdout (docs/json.md); errors as {\"error\": ...} too");
  decode->callback([&ctx, opts] { run_decode(ctx, *opts); });
}

}  // namespace hil::cli
