// SPDX-License-Identifier: MIT
#include "hil/canopen/sdo_abort.hpp"

#include <array>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace hil::canopen {
namespace {

constexpr std::array<std::pair<SdoAbort, std::string_view>, 31> k_texts{{
    {SdoAbort::none, "No abort"},
    {SdoAbort::toggle_bit, "Toggle bit not alternated"},
    {SdoAbort::timeout, "SDO protocol timed out"},
    {SdoAbort::command_specifier, "Client/server command specifier not valid or unknown"},
    {SdoAbort::block_size, "Invalid block size"},
    {SdoAbort::sequence_number, "Invalid sequence number"},
    {SdoAbort::crc, "CRC error"},
    {SdoAbort::out_of_memory, "Out of memory"},
    {SdoAbort::unsupported_access, "Unsupported access to an object"},
    {SdoAbort::write_only, "Attempt to read a write only object"},
    {SdoAbort::read_only, "Attempt to write a read only object"},
    {SdoAbort::no_object, "Object does not exist in the object dictionary"},
    {SdoAbort::not_mappable, "Object cannot be mapped to the PDO"},
    {SdoAbort::pdo_length, "The number and length of the objects to be mapped would exceed PDO length"},
    {SdoAbort::parameter_incompatible, "General parameter incompatibility reason"},
    {SdoAbort::internal_incompatible, "General internal incompatibility in the device"},
    {SdoAbort::hardware, "Access failed due to a hardware error"},
    {SdoAbort::type_mismatch, "Data type does not match, length of service parameter does not match"},
    {SdoAbort::length_too_high, "Data type does not match, length of service parameter too high"},
    {SdoAbort::length_too_low, "Data type does not match, length of service parameter too low"},
    {SdoAbort::no_sub_index, "Sub-index does not exist"},
    {SdoAbort::invalid_value, "Invalid value for parameter (download only)"},
    {SdoAbort::value_too_high, "Value of parameter written too high (download only)"},
    {SdoAbort::value_too_low, "Value of parameter written too low (download only)"},
    {SdoAbort::max_less_than_min, "Maximum value is less than minimum value"},
    {SdoAbort::resource_unavailable, "Resource not available: SDO connection"},
    {SdoAbort::general, "General error"},
    {SdoAbort::data_transfer, "Data cannot be transferred or stored to the application"},
    {SdoAbort::data_transfer_local, "Data cannot be transferred or stored to the application because of local control"},
    {SdoAbort::data_transfer_state,
     "Data cannot be transferred or stored to the application because of the present device state"},
    {SdoAbort::no_od, "Object dictionary dynamic generation fails or no object dictionary is present"},
}};

class SdoCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "canopen.sdo"; }
  std::string message(int v) const override {
    const auto code = static_cast<std::uint32_t>(v);
    return fmt::format("0x{:08X} {}", code, describe(static_cast<SdoAbort>(code)));
  }
};

}  // namespace

std::string_view describe(SdoAbort a) noexcept {
  if (a == SdoAbort::no_data) return "No data available";
  for (const auto& [code, text] : k_texts)
    if (code == a) return text;
  return "Unknown SDO abort code";
}

bool is_known_abort_code(std::uint32_t code) noexcept {
  if (code == static_cast<std::uint32_t>(SdoAbort::no_data)) return true;
  for (const auto& [c, text] : k_texts)
    if (static_cast<std::uint32_t>(c) == code && code != 0) return true;
  return false;
}

const std::error_category& sdo_category() noexcept {
  static const SdoCategory category;
  return category;
}

}  // namespace hil::canopen
