// SPDX-License-Identifier: MIT
#pragma once
// Error catalogues as data: each device's error numbers with their texts (German original where
// the manual is German, plus English), cause, remedy, reaction class and acknowledgement. Each
// catalogue provides an std::error_category, so a hil::Fault carries the manual's own number.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "hil/core/fault.hpp"

namespace hil::profiles {

/// What the device does when the error is raised (issue 6: message only, stop, drive off,
/// needs reset).
enum class Reaction { message, stop, drive_off, needs_reset };
[[nodiscard]] std::string_view to_string(Reaction r) noexcept;
[[nodiscard]] std::optional<Reaction> parse_reaction(std::string_view s) noexcept;

struct ErrorEntry {
  int code = 0;           ///< the manual's number (value of the error_code)
  std::string code_text;  ///< as the manual writes it: "4C", "F03", "2215"
  std::string text;       ///< English text
  std::string text_de;    ///< German original ("" when the manual is English)
  std::string cause;
  std::string remedy;
  Reaction reaction = Reaction::stop;
  std::string acknowledge;  ///< how it is cleared: "Clear key, External Clear edge or !CLEAR"
  std::string group;        ///< sub-list of the catalogue ("axis 2", "traversing", "power-on")
  std::string note;         ///< digest remark, decision taken
};

class ErrorCatalogue {
 public:
  ErrorCatalogue(std::string device, std::string id, std::string title, std::string code_format,
                 std::vector<ErrorEntry> entries);
  ErrorCatalogue(const ErrorCatalogue&) = delete;
  ErrorCatalogue& operator=(const ErrorCatalogue&) = delete;
  ~ErrorCatalogue();

  [[nodiscard]] const std::string& id() const noexcept { return id_; }  ///< "diagnostic"
  [[nodiscard]] const std::string& title() const noexcept { return title_; }
  [[nodiscard]] const std::string& code_format() const noexcept { return code_format_; }  ///< hex2, dec2, dec4, hex3
  [[nodiscard]] const std::vector<ErrorEntry>& entries() const noexcept { return entries_; }
  [[nodiscard]] const ErrorEntry* find(int code) const noexcept;
  /// Parses a code as the manual writes it (per code_format: "4C", "0x4C", "2215").
  [[nodiscard]] std::optional<int> parse_code(std::string_view text) const;
  [[nodiscard]] std::string format_code(int code) const;
  /// Category named "<device>.<id>" ("clm14.diagnostic"); message(code) = "<code> <text>".
  /// Lives as long as the catalogue (profiles from find_profile() live for the process).
  [[nodiscard]] const std::error_category& category() const noexcept;
  [[nodiscard]] std::error_code make_error_code(int code) const noexcept { return {code, category()}; }
  /// A fault carrying this catalogue's code; text = "<text>: <cause>" plus `context` ("axis 2").
  [[nodiscard]] hil::Fault make_fault(int code, std::string_view context = {}) const;

 private:
  class Category;
  std::string device_, id_, title_, code_format_;
  std::vector<ErrorEntry> entries_;
  std::unique_ptr<Category> category_;
};

}  // namespace hil::profiles
