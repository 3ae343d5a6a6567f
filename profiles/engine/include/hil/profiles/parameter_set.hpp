// SPDX-License-Identifier: MIT
#pragma once
// Parameter sets (a device's complete or partial parameterisation) and the parsers of each
// device's own text format. The parser is chosen by the profile's `text_format`:
//
//   clm-telegram   CLM1.4 K telegrams, one per line: "#␣K␣A101␣0010.00000$7D" (checksum checked
//                  when present), or the bare form "A101 0010.00000".
//   wf-md          WF 725/726 machine data: "MD 11 = -24537", "MD11 BCD 8002 4537",
//                  "MD11 HEX FFFF A027" (the two wire formats of §4.3).
//   s5-db          IP247 MD DB as a STEP 5 DB listing: "5: KH = 0000" … one data word per line;
//                  fields are decoded from their word offsets.
//   sinumerik-md   SINUMERIK System 3 / ELG data list on tape: "%" then "N<MD> P<value>" or
//                  "MD 396* = 180000"; bit MDs as 8-bit binary "MD 5002 = 00100010".
//   amk-db         AMKASYN SF commanding/init DB: "DW4 = 3", "DD10 = 20000", "DR0 = 2", "DL0 = 1",
//                  with "SF <type> <fct>" selecting the function's layout.
//
// Comments: ';' or '//' to end of line ('(' … ')' for sinumerik-md). Problems carry the line.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/field_value.hpp"
#include "hil/profiles/profile.hpp"
#include "hil/profiles/settings.hpp"

namespace hil::profiles {

struct SetEntry {
  ParamRef ref;
  ParamValue value;
  int line = 0;      ///< 1-based source line; 0 = not from a file
  std::string text;  ///< the source text of the value
};

/// What is wrong, where: used by the parsers and by validate().
struct Problem {
  int line = 0;         ///< 1-based; 0 = not tied to a line (missing parameter, rule over several)
  std::string param;    ///< concrete id(s): "A106", "MD12, MD11"
  std::string field;    ///< field name for multi-field parameters
  std::string value;    ///< the offending value(s) as text
  std::string rule;     ///< the rule: "range 0.1..50000", "MD12 < MD11 < MD13 < MD14"
  std::string message;  ///< what it means and what to do
  /// "set.txt:12: A106 = 60000.000: range 0.100..50000.000: maximum velocity above …"
  [[nodiscard]] std::string describe(std::string_view file = {}) const;
};

class ParameterSet {
 public:
  std::string device;
  std::vector<SetEntry> entries;  ///< in source order; one per concrete id

  [[nodiscard]] const SetEntry* find(std::string_view concrete_id) const;
  /// Inserts or replaces the entry of `e.ref.id()`.
  void set(SetEntry e);

 private:
  // normalised id → position in `entries`; checked on use, so direct edits of `entries` stay safe
  struct Slot {
    std::size_t pos;
    const ParamSpec* spec;
    std::optional<std::int64_t> instance;
  };
  std::map<std::string, Slot, std::less<>> index_;
  [[nodiscard]] const SetEntry* indexed(const std::string& key) const;
};

struct ParseResult {
  ParameterSet set;
  std::vector<Problem> problems;  ///< syntax and per-value codec problems; validation is separate
};

class ParameterSetParser {
 public:
  virtual ~ParameterSetParser() = default;
  /// Pure: text in, set + problems out. Never throws, never stops at the first problem.
  [[nodiscard]] virtual ParseResult parse(std::string_view text) const = 0;
  /// As parse(text), honouring format options among `settings` (SINUMERIK block_parity).
  [[nodiscard]] virtual ParseResult parse(std::string_view text, const Settings& settings) const {
    (void)settings;
    return parse(text);
  }
  /// The device's own text for `set` (parse(write(s)) reproduces s).
  [[nodiscard]] virtual std::string write(const ParameterSet& set) const = 0;
  /// As write(set), selecting variants with `settings` (AMKASYN: the SF type when the set has no init DB).
  [[nodiscard]] virtual std::string write(const ParameterSet& set, const Settings& settings) const {
    (void)settings;
    return write(set);
  }
  [[nodiscard]] virtual std::string_view format_name() const noexcept = 0;
};

/// The parser for `profile->text_format`; nullptr when the format is unknown.
[[nodiscard]] std::unique_ptr<ParameterSetParser> make_parameter_set_parser(std::shared_ptr<const Profile> profile);

/// CLM1.4 serial checksum (§9.2 Fig. 9-12): two's complement of (hi + lo byte of the byte sum).
[[nodiscard]] std::uint8_t clm_checksum(std::string_view bytes) noexcept;

}  // namespace hil::profiles
