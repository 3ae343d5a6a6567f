// SPDX-License-Identifier: MIT
#pragma once
// Object dictionary (CiA 301 §7.4): sub-objects keyed by (index, sub-index) holding their value
// as little-endian wire bytes, with data type, access type, PDO mappability and limits.
// SDO writes are checked (access, length, limits, per-object validators) and answer with the
// CiA 301 abort code; the device writes its own process values with set_*(), bypassing access.
// Thread: one owner (the node's executor); not thread-safe.

#include <concepts>
#include <cstdint>
#include <cstring>
#include <expected>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "hil/canopen/data_type.hpp"
#include "hil/canopen/sdo_abort.hpp"

namespace hil::canopen {

struct Variable {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::string name;
  DataType type = DataType::unsigned8;
  Access access = Access::rw;
  bool pdo_mappable = false;
  std::vector<std::uint8_t> value;        ///< wire bytes (LE); fixed types hold exactly data_type_size()
  std::optional<std::int64_t> low, high;  ///< inclusive limits for integer types (EDS LowLimit/HighLimit)

  [[nodiscard]] std::uint32_t key() const noexcept { return (std::uint32_t{index} << 8) | sub; }
  /// Value as a signed/unsigned integer (sign-extended for signed types); 0 for non-integers.
  [[nodiscard]] std::int64_t as_int() const noexcept;
  [[nodiscard]] std::uint64_t as_uint() const noexcept;
};

/// Encode an integer into `size` little-endian bytes (two's complement, truncated).
void encode_int(std::int64_t v, std::size_t size, std::uint8_t* out) noexcept;
/// Decode `bytes` as a little-endian integer, sign-extending when `sign` is true.
[[nodiscard]] std::int64_t decode_int(std::span<const std::uint8_t> bytes, bool sign) noexcept;

class ObjectDictionary {
 public:
  /// Checks an SDO write of `bytes` to `var` before it is stored; return SdoAbort::none to accept.
  using Validator = std::function<SdoAbort(const Variable& var, std::span<const std::uint8_t> bytes)>;
  /// Told after a value changed through write() or write_mapped().
  using Observer = std::function<void(const Variable& var)>;

  ObjectDictionary() = default;
  ObjectDictionary(const ObjectDictionary& other);
  ObjectDictionary& operator=(const ObjectDictionary& other);
  ObjectDictionary(ObjectDictionary&&) noexcept = default;
  ObjectDictionary& operator=(ObjectDictionary&&) noexcept = default;

  /// Add (or replace) a sub-object. Fixed-size values are resized to the type's size.
  Variable& add(Variable v);
  [[nodiscard]] Variable* find(std::uint16_t index, std::uint8_t sub) noexcept;
  [[nodiscard]] const Variable* find(std::uint16_t index, std::uint8_t sub) const noexcept;
  [[nodiscard]] bool has_object(std::uint16_t index) const noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return vars_.size(); }
  [[nodiscard]] const std::map<std::uint32_t, Variable>& variables() const noexcept { return vars_; }

  /// SDO upload: the value, or no_object / no_sub_index / write_only.
  [[nodiscard]] std::expected<std::span<const std::uint8_t>, SdoAbort> read(std::uint16_t index,
                                                                            std::uint8_t sub) const;
  /// SDO download: access, length (type_mismatch / length_too_high / length_too_low), limits
  /// (value_too_high / value_too_low), then the index's validator; stores and notifies on success.
  SdoAbort write(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> bytes);
  /// RPDO write (mapping already validated): length must match; no access check.
  SdoAbort write_mapped(Variable& var, std::span<const std::uint8_t> bytes);

  void set_validator(std::uint16_t index, Validator v) { validators_[index] = std::move(v); }
  void add_observer(std::uint16_t index, Observer o) { observers_[index].push_back(std::move(o)); }

  /// Device-side access by value; no access check, no observers. Missing objects are ignored
  /// (set) or read as 0 (get): the device's own objects come from its EDS and are verified at load.
  void set_int(std::uint16_t index, std::uint8_t sub, std::int64_t v) noexcept;
  [[nodiscard]] std::int64_t get_int(std::uint16_t index, std::uint8_t sub) const noexcept;
  void set_bytes(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> bytes);

  /// Largest accepted variable-length value (domains, strings) in bytes. Default 64 KiB.
  void set_max_value_size(std::size_t n) noexcept { max_value_size_ = n; }
  [[nodiscard]] std::size_t max_value_size() const noexcept { return max_value_size_; }

 private:
  void notify(const Variable& v) const;
  void rebuild_index();
  std::map<std::uint32_t, Variable> vars_;
  std::unordered_map<std::uint32_t, Variable*> index_;  ///< O(1) find() on the cyclic path
  std::map<std::uint16_t, Validator> validators_;
  std::map<std::uint16_t, std::vector<Observer>> observers_;
  std::size_t max_value_size_ = 64 * 1024;
};

}  // namespace hil::canopen
