// SPDX-License-Identifier: MIT
#include "hil/canopen/object_dictionary.hpp"

namespace hil::canopen {

void encode_int(std::int64_t v, std::size_t size, std::uint8_t* out) noexcept {
  auto u = static_cast<std::uint64_t>(v);
  for (std::size_t i = 0; i < size; ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

std::int64_t decode_int(std::span<const std::uint8_t> bytes, bool sign) noexcept {
  std::uint64_t u = 0;
  const auto n = bytes.size() > 8 ? 8 : bytes.size();
  for (std::size_t i = 0; i < n; ++i) u |= std::uint64_t{bytes[i]} << (8 * i);
  if (sign && n > 0 && n < 8 && (bytes[n - 1] & 0x80)) u |= ~std::uint64_t{0} << (8 * n);
  return static_cast<std::int64_t>(u);
}

std::int64_t Variable::as_int() const noexcept {
  if (!is_integer(type)) return 0;
  return decode_int(value, is_signed(type));
}
std::uint64_t Variable::as_uint() const noexcept {
  return static_cast<std::uint64_t>(as_int());
}

ObjectDictionary::ObjectDictionary(const ObjectDictionary& other)
    : vars_(other.vars_),
      validators_(other.validators_),
      observers_(other.observers_),
      max_value_size_(other.max_value_size_) {
  rebuild_index();
}

ObjectDictionary& ObjectDictionary::operator=(const ObjectDictionary& other) {
  if (this != &other) {
    vars_ = other.vars_;
    validators_ = other.validators_;
    observers_ = other.observers_;
    max_value_size_ = other.max_value_size_;
    rebuild_index();
  }
  return *this;
}

void ObjectDictionary::rebuild_index() {
  index_.clear();
  index_.reserve(vars_.size());
  for (auto& [key, v] : vars_) index_[key] = &v;
}

Variable& ObjectDictionary::add(Variable v) {
  if (const auto n = data_type_size(v.type); n != 0) v.value.resize(n, 0);
  const auto key = v.key();
  auto [it, inserted] = vars_.insert_or_assign(key, std::move(v));
  index_[key] = &it->second;
  return it->second;
}

Variable* ObjectDictionary::find(std::uint16_t index, std::uint8_t sub) noexcept {
  auto it = index_.find((std::uint32_t{index} << 8) | sub);
  return it == index_.end() ? nullptr : it->second;
}
const Variable* ObjectDictionary::find(std::uint16_t index, std::uint8_t sub) const noexcept {
  auto it = index_.find((std::uint32_t{index} << 8) | sub);
  return it == index_.end() ? nullptr : it->second;
}

bool ObjectDictionary::has_object(std::uint16_t index) const noexcept {
  auto it = vars_.lower_bound(std::uint32_t{index} << 8);
  return it != vars_.end() && (it->first >> 8) == index;
}

std::expected<std::span<const std::uint8_t>, SdoAbort> ObjectDictionary::read(std::uint16_t index,
                                                                              std::uint8_t sub) const {
  const auto* v = find(index, sub);
  if (v == nullptr) return std::unexpected(has_object(index) ? SdoAbort::no_sub_index : SdoAbort::no_object);
  if (!readable(v->access)) return std::unexpected(SdoAbort::write_only);
  return std::span<const std::uint8_t>(v->value);
}

SdoAbort ObjectDictionary::write(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> bytes) {
  auto* v = find(index, sub);
  if (v == nullptr) return has_object(index) ? SdoAbort::no_sub_index : SdoAbort::no_object;
  if (!writable(v->access)) return SdoAbort::read_only;
  const auto n = data_type_size(v->type);
  if (n != 0) {
    if (bytes.size() > n) return SdoAbort::length_too_high;
    if (bytes.size() < n) return SdoAbort::length_too_low;
    if (is_integer(v->type) && (v->low || v->high)) {
      const auto x = decode_int(bytes, is_signed(v->type));
      if (is_signed(v->type) || n < 8) {
        if (v->high && x > *v->high) return SdoAbort::value_too_high;
        if (v->low && x < *v->low) return SdoAbort::value_too_low;
      } else {
        const auto ux = static_cast<std::uint64_t>(x);
        if (v->high && ux > static_cast<std::uint64_t>(*v->high)) return SdoAbort::value_too_high;
        if (v->low && ux < static_cast<std::uint64_t>(*v->low)) return SdoAbort::value_too_low;
      }
    }
    if (v->type == DataType::boolean && bytes[0] > 1) return SdoAbort::invalid_value;
  } else if (bytes.size() > max_value_size_) {
    return SdoAbort::length_too_high;
  }
  if (auto it = validators_.find(index); it != validators_.end()) {
    if (const auto a = it->second(*v, bytes); a != SdoAbort::none) return a;
  }
  v->value.assign(bytes.begin(), bytes.end());
  notify(*v);
  return SdoAbort::none;
}

SdoAbort ObjectDictionary::write_mapped(Variable& var, std::span<const std::uint8_t> bytes) {
  if (bytes.size() != var.value.size()) return SdoAbort::type_mismatch;
  if (std::memcmp(var.value.data(), bytes.data(), bytes.size()) == 0) return SdoAbort::none;
  std::memcpy(var.value.data(), bytes.data(), bytes.size());
  notify(var);
  return SdoAbort::none;
}

void ObjectDictionary::notify(const Variable& v) const {
  if (auto it = observers_.find(v.index); it != observers_.end())
    for (const auto& o : it->second) o(v);
}

void ObjectDictionary::set_int(std::uint16_t index, std::uint8_t sub, std::int64_t x) noexcept {
  if (auto* v = find(index, sub); v != nullptr && !v->value.empty() && is_integer(v->type))
    encode_int(x, v->value.size(), v->value.data());
}

std::int64_t ObjectDictionary::get_int(std::uint16_t index, std::uint8_t sub) const noexcept {
  const auto* v = find(index, sub);
  return v == nullptr ? 0 : v->as_int();
}

void ObjectDictionary::set_bytes(std::uint16_t index, std::uint8_t sub, std::span<const std::uint8_t> bytes) {
  if (auto* v = find(index, sub)) {
    if (const auto n = data_type_size(v->type); n != 0) {
      v->value.assign(n, 0);
      std::memcpy(v->value.data(), bytes.data(), bytes.size() < n ? bytes.size() : n);
    } else {
      v->value.assign(bytes.begin(), bytes.end());
    }
  }
}

}  // namespace hil::canopen
