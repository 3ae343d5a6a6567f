// SPDX-License-Identifier: MIT
#pragma once
// The device profile model: settings, parameters (fields, ranges, steps, defaults, when they take
// effect, protection), cross-parameter constraints, error catalogues and descriptive tables (I/O
// maps, markers, block layouts). Built by load_profile() from the YAML in profiles/devices/;
// immutable afterwards and safe to share between threads.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/bit_field.hpp"
#include "hil/profiles/catalogue.hpp"
#include "hil/profiles/decimal_text.hpp"
#include "hil/profiles/expression.hpp"
#include "hil/profiles/field_value.hpp"
#include "hil/profiles/fixed_point.hpp"

namespace hil::profiles {

/// When a changed parameter becomes effective.
enum class TakesEffect { immediately, leaving_parameter_mode, after_reset, after_power_cycle };
/// Who may change it.
enum class Protection {
  none,             ///< operator
  machine_builder,  ///< change only with the machine builder's permission (CLM '*')
  read_only,        ///< displayed, never written (service data, software version)
  system,           ///< written by the system/standard software only (WF MD 50)
};
[[nodiscard]] std::string_view to_string(TakesEffect t) noexcept;
[[nodiscard]] std::string_view to_string(Protection p) noexcept;

enum class FieldType {
  number,      ///< decimal number in a fixed text field (or a word, see Encoding)
  choice,      ///< integer from a list of meanings
  io_address,  ///< CLM I/O or marker bit "I1.00.0", "Q1.02.7", "M2.02.0"; "00.00.0" = unused
  hex,         ///< hex digits ("FF0000")
  bits,        ///< bit field word (value = the word)
  reserved,    ///< fixed text, carried unchanged
};

/// A range bound or step: a literal or an expression over settings/parameters, optionally only
/// when `when` holds (e.g. `resolution == 10`).
struct Bound {
  std::optional<Decimal> literal;
  Expression expr;
  [[nodiscard]] bool is_set() const noexcept { return literal.has_value() || !expr.empty(); }
  [[nodiscard]] std::string text() const;
};
struct RangeRule {
  Expression when;
  Bound min, max;
  std::vector<Decimal> allowed;  ///< discrete allowed values ("1, 2, 4"); empty = interval only
};
struct StepRule {
  Expression when;
  Bound step;
};
struct Choice {
  std::int64_t value = 0;
  std::string meaning;
};

/// How one field is put on the wire (Profile::wire gives the default for the device).
enum class Encoding {
  text,        ///< decimal/io/hex text per template (CLM telegram data)
  bcd_binary,  ///< WF 725/726: one 32-bit value as BCD word (Profile::bcd) and binary word
  kf,          ///< S5 KF: 16-bit signed word
  kh,          ///< S5 KH: 16-bit word, hex
  ky,          ///< S5 KY: two bytes "DL,DR"
  kd,          ///< S5 DD/KD: 32-bit two's complement, high word first
  byte_l,      ///< left (high) byte of a word (S5 DL)
  byte_r,      ///< right (low) byte of a word (S5 DR)
  fixed,       ///< fixed point in a word (FieldSpec::fixed)
};
[[nodiscard]] std::optional<Encoding> parse_encoding(std::string_view s) noexcept;
[[nodiscard]] std::string_view to_string(Encoding e) noexcept;

struct FieldSpec {
  std::string name;
  std::string meaning;
  std::string unit;
  FieldType type = FieldType::number;
  DecimalTextFormat text;             ///< number/choice text template ("+6.3")
  int hex_digits = 0;                 ///< hex: number of digits
  std::vector<std::string> io_types;  ///< io_address: allowed letters, e.g. {"I"} or {"Q","M"}
  std::string fixed_text;             ///< reserved: the text carried
  std::vector<RangeRule> ranges;      ///< first rule whose `when` holds applies
  std::vector<StepRule> steps;
  std::vector<Choice> choices;
  BitFieldFormat bits;
  bool binary_text = false;          ///< bits: text form is bits.bits binary digits, MSB first ("00100010")
  std::optional<Encoding> encoding;  ///< overrides the profile's wire encoding
  FixedPointFormat fixed;            ///< Encoding::fixed
  int word = -1;                     ///< word-image devices: data word offset of this field
  std::optional<FieldValue> default_value;
  std::string note;  ///< open point of the manual and the choice made
};

/// One meaning of a parameter; WF 725/726 MDs have several (per control type / encoder).
struct ParamVariant {
  Expression when;  ///< empty = always
  std::string name;
  std::string meaning;
  std::vector<FieldSpec> fields;
  TakesEffect takes_effect = TakesEffect::leaving_parameter_mode;
  Protection protection = Protection::none;
  std::string note;
};

struct ParamSpec {
  std::string id;                       ///< template id: "Ax06", "MD11", "MD204*", "B002"
  std::string pattern;                  ///< concrete id pattern with "{axis}" ("A{axis}06"); "" = id
  std::vector<std::string> aliases;     ///< further names resolve() accepts ("fmax" for IP247 "DW5")
  std::string instance_key;             ///< "axis" when instanced
  std::vector<std::int64_t> instances;  ///< values of instance_key
  int number = 0;                       ///< number inside its group
  std::string group;                    ///< "axis", "general", "encoder", "MD words", …
  Expression required;                  ///< empty = optional; else must be present when true
  std::vector<ParamVariant> variants;   ///< at least one
  std::string source;                   ///< manual section

  /// Concrete id for an instance ("A106" for axis 1).
  [[nodiscard]] std::string concrete_id(std::optional<std::int64_t> instance) const;
};

/// A resolved parameter reference: spec + instance (axis) it was addressed with.
struct ParamRef {
  const ParamSpec* spec = nullptr;
  std::optional<std::int64_t> instance;
  [[nodiscard]] std::string id() const { return spec ? spec->concrete_id(instance) : std::string(); }
};

struct SettingSpec {
  std::string name;
  std::string meaning;
  std::vector<ExprValue> values;  ///< allowed values; empty = any
  std::optional<ExprValue> default_value;
  Expression from;  ///< derived from parameters when they are present
  std::string note;
};

struct Constraint {
  std::string id;
  Expression rule;
  Expression when;       ///< empty = always
  std::string for_each;  ///< instance key ("axis"): checked once per instance
  std::vector<std::int64_t> instances;
  std::string message;  ///< what it means and which error the device raises
  std::string source;
};

struct Decision {
  std::string topic;
  std::string choice;
  std::string configurable;  ///< setting/parameter that changes it
};

/// A descriptive table (I/O map, markers, variables, block layouts): rows of key → text.
using Table = std::vector<std::map<std::string, std::string>>;

struct WireSpec {
  Encoding encoding = Encoding::text;
  std::string separator = " ";  ///< between text fields
  BcdFormat bcd{8, BcdSign::bit31};
  int binary_bits = 32;
  bool low_word_first = false;  ///< 32-bit values: low word at the lower address (AMKASYN DD)
};

class Profile {
 public:
  std::string device;  ///< "clm14"
  std::string title;
  std::string manual;
  std::string description;
  std::string text_format;  ///< parameter-set parser name (see parameter_set.hpp)
  std::string source_file;  ///< YAML it was loaded from
  WireSpec wire;
  std::vector<SettingSpec> settings;
  std::vector<ParamSpec> parameters;
  std::vector<Constraint> constraints;
  std::vector<std::unique_ptr<ErrorCatalogue>> catalogues;
  std::vector<Decision> decisions;
  std::map<std::string, Table> tables;

  /// "A106", "a106", "MD 11", "MD11", "B002" → spec + instance. Case-insensitive, spaces ignored.
  [[nodiscard]] std::optional<ParamRef> resolve(std::string_view id) const;
  /// Every concrete id in profile order ("B000"…, "A100"…"A442", …).
  [[nodiscard]] std::vector<ParamRef> all_refs() const;
  [[nodiscard]] const ErrorCatalogue* catalogue(std::string_view id) const;
  [[nodiscard]] const SettingSpec* setting(std::string_view name) const;

  /// An instanced parameter by its template id ("Ax06", "MD204*") or its pattern without the
  /// placeholder ("MD204"); nullptr when none.
  [[nodiscard]] const ParamSpec* resolve_template(std::string_view id) const;

  /// Builds the id index; called by the loader after filling the members.
  void index();

 private:
  std::map<std::string, ParamRef, std::less<>> index_;
  std::map<std::string, const ParamSpec*, std::less<>> templates_;
};

/// Normalised lookup key for ids: upper case, spaces removed ("md 11" → "MD11").
[[nodiscard]] std::string normalise_id(std::string_view id);

}  // namespace hil::profiles
