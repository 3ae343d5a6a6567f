// SPDX-License-Identifier: MIT
#include "hil/canopen/data_type.hpp"

#include <cctype>
#include <string>

namespace hil::canopen {

std::optional<DataType> data_type_from_code(std::uint32_t code) noexcept {
  if ((code >= 0x01 && code <= 0x0D) || (code >= 0x0F && code <= 0x16) || (code >= 0x18 && code <= 0x1B))
    return static_cast<DataType>(code);
  return std::nullopt;
}

std::size_t data_type_size(DataType t) noexcept {
  switch (t) {
    case DataType::boolean:
    case DataType::integer8:
    case DataType::unsigned8:
      return 1;
    case DataType::integer16:
    case DataType::unsigned16:
      return 2;
    case DataType::integer24:
    case DataType::unsigned24:
      return 3;
    case DataType::integer32:
    case DataType::unsigned32:
    case DataType::real32:
      return 4;
    case DataType::integer40:
    case DataType::unsigned40:
      return 5;
    case DataType::integer48:
    case DataType::unsigned48:
    case DataType::time_of_day:
    case DataType::time_difference:
      return 6;
    case DataType::integer56:
    case DataType::unsigned56:
      return 7;
    case DataType::integer64:
    case DataType::unsigned64:
    case DataType::real64:
      return 8;
    case DataType::visible_string:
    case DataType::octet_string:
    case DataType::unicode_string:
    case DataType::domain:
      return 0;
  }
  return 0;
}

bool is_signed(DataType t) noexcept {
  switch (t) {
    case DataType::integer8:
    case DataType::integer16:
    case DataType::integer24:
    case DataType::integer32:
    case DataType::integer40:
    case DataType::integer48:
    case DataType::integer56:
    case DataType::integer64:
      return true;
    default:
      return false;
  }
}

bool is_variable_length(DataType t) noexcept {
  return data_type_size(t) == 0;
}

bool is_integer(DataType t) noexcept {
  return !is_variable_length(t) && t != DataType::real32 && t != DataType::real64 && t != DataType::time_of_day &&
         t != DataType::time_difference;
}

std::string_view to_string(DataType t) noexcept {
  switch (t) {
    case DataType::boolean:
      return "BOOLEAN";
    case DataType::integer8:
      return "INTEGER8";
    case DataType::integer16:
      return "INTEGER16";
    case DataType::integer32:
      return "INTEGER32";
    case DataType::unsigned8:
      return "UNSIGNED8";
    case DataType::unsigned16:
      return "UNSIGNED16";
    case DataType::unsigned32:
      return "UNSIGNED32";
    case DataType::real32:
      return "REAL32";
    case DataType::visible_string:
      return "VISIBLE_STRING";
    case DataType::octet_string:
      return "OCTET_STRING";
    case DataType::unicode_string:
      return "UNICODE_STRING";
    case DataType::time_of_day:
      return "TIME_OF_DAY";
    case DataType::time_difference:
      return "TIME_DIFFERENCE";
    case DataType::domain:
      return "DOMAIN";
    case DataType::integer24:
      return "INTEGER24";
    case DataType::real64:
      return "REAL64";
    case DataType::integer40:
      return "INTEGER40";
    case DataType::integer48:
      return "INTEGER48";
    case DataType::integer56:
      return "INTEGER56";
    case DataType::integer64:
      return "INTEGER64";
    case DataType::unsigned24:
      return "UNSIGNED24";
    case DataType::unsigned40:
      return "UNSIGNED40";
    case DataType::unsigned48:
      return "UNSIGNED48";
    case DataType::unsigned56:
      return "UNSIGNED56";
    case DataType::unsigned64:
      return "UNSIGNED64";
  }
  return "UNKNOWN";
}

std::optional<Access> access_from_string(std::string_view s) noexcept {
  std::string lower;
  for (char c : s) lower.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  if (lower == "ro") return Access::ro;
  if (lower == "wo") return Access::wo;
  if (lower == "rw") return Access::rw;
  if (lower == "rwr") return Access::rwr;
  if (lower == "rww") return Access::rww;
  if (lower == "const") return Access::const_;
  return std::nullopt;
}

std::string_view to_string(Access a) noexcept {
  switch (a) {
    case Access::ro:
      return "ro";
    case Access::wo:
      return "wo";
    case Access::rw:
      return "rw";
    case Access::rwr:
      return "rwr";
    case Access::rww:
      return "rww";
    case Access::const_:
      return "const";
  }
  return "?";
}

}  // namespace hil::canopen
