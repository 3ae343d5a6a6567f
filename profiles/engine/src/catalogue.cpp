// SPDX-License-Identifier: MIT
#include "hil/profiles/catalogue.hpp"

#include <fmt/format.h>

#include <charconv>

namespace hil::profiles {

std::string_view to_string(Reaction r) noexcept {
  switch (r) {
    case Reaction::message:
      return "message";
    case Reaction::stop:
      return "stop";
    case Reaction::drive_off:
      return "drive_off";
    case Reaction::needs_reset:
      return "needs_reset";
  }
  return "?";
}

std::optional<Reaction> parse_reaction(std::string_view s) noexcept {
  if (s == "message") return Reaction::message;
  if (s == "stop") return Reaction::stop;
  if (s == "drive_off") return Reaction::drive_off;
  if (s == "needs_reset") return Reaction::needs_reset;
  return std::nullopt;
}

class ErrorCatalogue::Category final : public std::error_category {
 public:
  explicit Category(const ErrorCatalogue& c) : c_(c), name_(c.device_ + "." + c.id_) {}
  const char* name() const noexcept override { return name_.c_str(); }
  std::string message(int code) const override {
    if (const auto* e = c_.find(code)) return fmt::format("{} {}", e->code_text, e->text);
    return fmt::format("{} unknown {} code", c_.format_code(code), c_.title_);
  }

 private:
  const ErrorCatalogue& c_;
  std::string name_;
};

ErrorCatalogue::ErrorCatalogue(std::string device, std::string id, std::string title, std::string code_format,
                               std::vector<ErrorEntry> entries)
    : device_(std::move(device)),
      id_(std::move(id)),
      title_(std::move(title)),
      code_format_(std::move(code_format)),
      entries_(std::move(entries)),
      category_(std::make_unique<Category>(*this)) {}

ErrorCatalogue::~ErrorCatalogue() = default;

const ErrorEntry* ErrorCatalogue::find(int code) const noexcept {
  for (const auto& e : entries_)
    if (e.code == code) return &e;
  return nullptr;
}

std::optional<int> ErrorCatalogue::parse_code(std::string_view text) const {
  std::string_view t = text;
  while (!t.empty() && t.front() == ' ') t.remove_prefix(1);
  while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
  int base = code_format_.starts_with("hex") ? 16 : 10;
  if (t.starts_with("0x") || t.starts_with("0X")) {
    base = 16;
    t.remove_prefix(2);
  }
  // Code formats with a letter prefix ("F03" for IP247 COM247 MD errors) keep their text; match it first.
  for (const auto& e : entries_)
    if (e.code_text == t) return e.code;
  int v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v, base);
  if (ec != std::errc{} || p != t.data() + t.size() || t.empty()) return std::nullopt;
  return v;
}

std::string ErrorCatalogue::format_code(int code) const {
  if (const auto* e = find(code)) return e->code_text;
  if (code_format_ == "hex2") return fmt::format("{:02X}", code);
  if (code_format_ == "hex4") return fmt::format("{:04X}", code);
  if (code_format_ == "dec2") return fmt::format("{:02d}", code);
  return std::to_string(code);
}

const std::error_category& ErrorCatalogue::category() const noexcept {
  return *category_;
}

hil::Fault ErrorCatalogue::make_fault(int code, std::string_view context) const {
  hil::Fault f;
  f.code = make_error_code(code);
  if (const auto* e = find(code)) {
    f.text = e->text;
    if (!e->cause.empty()) f.text += ": " + e->cause;
    if (!e->remedy.empty()) f.text += "; remedy: " + e->remedy;
  } else {
    f.text = fmt::format("unknown {} code {}", title_, format_code(code));
  }
  if (!context.empty()) f.text += fmt::format(" ({})", context);
  return f;
}

}  // namespace hil::profiles
