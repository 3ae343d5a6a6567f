// SPDX-License-Identifier: MIT
// DeviceData over the CLM1.4 device profile (profiles/devices/clm14.yaml via hil::profiles).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <map>

#include "hil/profiles/loader.hpp"
#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"
#include "hil/serial/clm14/device_data.hpp"

namespace hil::serial::clm14 {

namespace {

namespace pf = hil::profiles;

// The CLM program command set (manual §5.7, digest clm14.md §4.2). Program syntax is not part of
// the parameter profile; operand widths are checked as far as the manual's table survived.
constexpr std::array<std::string_view, 55> program_commands{
    "ACC", "AEA", "AEO", "AKN", "AKP", "APE", "BAC", "BCE", "BIC", "BIO", "BPA", "CID", "CIO", "CLC",
    "CON", "COU", "CPJ", "CPL", "CPS", "CST", "CVT", "EOS", "FAK", "FOL", "FUN", "HOM", "JMP", "JSR",
    "JST", "JTK", "LMK", "LML", "LMR", "MAT", "MLO", "MLT", "NOP", "PBK", "POA", "POI", "PSA", "PSI",
    "REP", "RMI", "RSV", "RTM", "RTS", "SAC", "SET", "SRM", "SRP", "TXT", "VCC", "VEO", "WAI"};

class ProfileData final : public DeviceData {
 public:
  explicit ProfileData(std::shared_ptr<const pf::Profile> p) : p_(std::move(p)) {
    settings_["hardware_axes"] = pf::ExprValue{4.0L};
    defaults_ = pf::default_set(*p_, settings_);
    for (const auto& r : p_->all_refs()) {
      const auto* e = defaults_.find(r.id());
      const auto* v = variant(r);
      if (e == nullptr || v == nullptr) continue;
      if (auto img = pf::encode_value(*p_, *v, e->value)) default_text_[r.id()] = img->text;
    }
  }

  std::vector<std::string> parameter_numbers(int axes) const override {
    std::vector<std::string> out;
    for (const auto& r : p_->all_refs()) {
      if (r.instance && *r.instance > axes) continue;
      out.push_back(r.id());
    }
    // Transfer order of the manual: B, then A1xx..A4xx, then C.
    std::stable_sort(out.begin(), out.end(), [](const std::string& a, const std::string& b) {
      const auto rank = [](char c) { return c == 'B' ? 0 : c == 'A' ? 1 : 2; };
      if (rank(a[0]) != rank(b[0])) return rank(a[0]) < rank(b[0]);
      return a < b;
    });
    return out;
  }

  std::string parameter_default(std::string_view number) const override {
    const auto ref = p_->resolve(number);
    if (!ref) return {};
    const auto it = default_text_.find(ref->id());
    return it == default_text_.end() ? std::string{} : it->second;
  }

  std::expected<std::string, FieldRejection> check_parameter(std::string_view number,
                                                             std::string_view data) const override {
    const auto ref = p_->resolve(number);
    if (!ref) return std::unexpected(FieldRejection{7, fmt::format("{} is not a CLM1.4 parameter", number)});
    const auto* v = variant(*ref);
    if (v == nullptr) return std::unexpected(FieldRejection{7, fmt::format("{} does not apply to this unit", number)});
    auto value = pf::decode_wire(*p_, *v, data);
    if (!value) return std::unexpected(FieldRejection{2, fmt::format("{} '{}': {}", number, data, value.error())});
    const pf::Scope scope(*p_, nullptr, settings_, ref->instance, ref->spec->instance_key);
    std::vector<std::string> why;
    for (std::size_t i = 0; i < v->fields.size() && i < value->size(); ++i)
      for (const auto& prob : pf::check_field(*ref, v->fields[i], (*value)[i], scope)) why.push_back(prob.describe());
    if (!why.empty()) return std::unexpected(FieldRejection{3, fmt::format("{}", fmt::join(why, "; "))});
    auto img = pf::encode_value(*p_, *v, *value);
    if (!img) return std::unexpected(FieldRejection{2, fmt::format("{} '{}': {}", number, data, img.error())});
    return img->text;
  }

  std::expected<std::string, FieldRejection> check_program_line(std::string_view line) const override {
    while (!line.empty() && line.back() == ' ') line.remove_suffix(1);
    while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
    const std::string_view mne = line.substr(0, 3);
    if (line.size() < 3 || std::find(program_commands.begin(), program_commands.end(), mne) == program_commands.end() ||
        (line.size() > 3 && line[3] != ' '))
      return std::unexpected(
          FieldRejection{13, fmt::format("'{}' is not a CLM command (ACC ... WAI)", line.substr(0, 8))});
    const std::string_view ops = line.size() > 4 ? line.substr(4) : std::string_view{};
    if (ops.size() > 32)
      return std::unexpected(FieldRejection{3, fmt::format("{} operands longer than 32 characters", mne)});
    for (char c : ops) {
      const bool txt_ok = mne == "TXT" && c >= 32 && c <= 95 && c != '$' && c != '\\';
      const bool ok = (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z') || c == ' ' || c == '+' || c == '-' ||
                      c == '.' || c == ',' || c == '<' || c == '>' || c == '=' || c == '*' || c == '/';
      if (!ok && !txt_ok)
        return std::unexpected(FieldRejection{3, fmt::format("{}: character '{}' not allowed in operands", mne, c)});
    }
    const bool no_operands = mne == "NOP" || mne == "RTS" || mne == "EOS";
    if (no_operands && !ops.empty())
      return std::unexpected(FieldRejection{3, fmt::format("{} takes no operands", mne)});
    if (!no_operands && ops.empty()) return std::unexpected(FieldRejection{3, fmt::format("{} needs operands", mne)});
    return std::string(line);
  }

  std::string serial_error_text(int code) const override { return text_of("serial", code); }
  std::string fault_text(int code) const override { return text_of("diagnostic", code); }
  std::string identification() const override { return "CLM01.4-P-E-4-B CLM1.4-LAP-05VRS"; }

 private:
  const pf::ParamVariant* variant(const pf::ParamRef& ref) const {
    const pf::Scope scope(*p_, &defaults_, settings_, ref.instance, ref.spec->instance_key);
    return pf::select_variant(ref, scope);
  }
  std::string text_of(std::string_view catalogue, int code) const {
    if (const auto* c = p_->catalogue(catalogue))
      if (const auto* e = c->find(code)) return e->text;
    return fmt::format("error {:02d}", code);
  }

  std::shared_ptr<const pf::Profile> p_;
  pf::Settings settings_;
  pf::ParameterSet defaults_;
  std::map<std::string, std::string, std::less<>> default_text_;
};

}  // namespace

std::expected<std::shared_ptr<const DeviceData>, std::string> load_device_data(const std::string& path) {
  auto p = path.empty() ? pf::find_profile("clm14") : pf::load_profile(path);
  if (!p) return std::unexpected(p.error().describe());
  return std::shared_ptr<const DeviceData>(std::make_shared<ProfileData>(*p));
}

}  // namespace hil::serial::clm14
