// SPDX-License-Identifier: MIT
#include "hil/cia402/error_code.hpp"

#include <array>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace hil::cia402 {
namespace {

constexpr std::array<std::pair<std::uint16_t, std::string_view>, 40> k_exact{{
    {0x0000, "No error (error reset)"},
    {0x1000, "Generic error"},
    {0x2300, "Current, device output side"},
    {0x2310, "Continuous over-current"},
    {0x2320, "Short circuit / earth leakage"},
    {0x2330, "Earth leakage"},
    {0x3110, "Mains over-voltage"},
    {0x3120, "Mains under-voltage"},
    {0x3210, "DC link over-voltage"},
    {0x3220, "DC link under-voltage"},
    {0x4210, "Excess temperature device"},
    {0x4310, "Excess temperature drive"},
    {0x5112, "Supply low voltage"},
    {0x5400, "Power section"},
    {0x5441, "Safe torque off active"},
    {0x6010, "Software reset (watchdog)"},
    {0x6100, "Internal software"},
    {0x6320, "Parameter error"},
    {0x7110, "Brake chopper"},
    {0x7120, "Motor"},
    {0x7121, "Motor blocked"},
    {0x7122, "Motor error or commutation malfunction"},
    {0x7300, "Sensor"},
    {0x7305, "Incremental sensor 1 fault"},
    {0x7306, "Incremental sensor 2 fault"},
    {0x7310, "Speed"},
    {0x7320, "Position"},
    {0x8110, "CAN overrun (objects lost)"},
    {0x8120, "CAN in error passive mode"},
    {0x8130, "Life guard error or heartbeat error"},
    {0x8140, "Recovered from bus off"},
    {0x8210, "PDO not processed due to length error"},
    {0x8220, "PDO length exceeded"},
    {0x8250, "RPDO timeout"},
    {0x8400, "Velocity speed controller"},
    {0x8500, "Position controller"},
    {0x8611, "Following error"},
    {0x8612, "Reference limit"},
    {0xFF00, "Device specific"},
    {0x9000, "External error"},
}};

constexpr std::array<std::pair<std::uint16_t, std::string_view>, 12> k_groups{{
    {0x1000, "Generic error"},
    {0x2000, "Current"},
    {0x3000, "Voltage"},
    {0x4000, "Temperature"},
    {0x5000, "Device hardware"},
    {0x6000, "Device software"},
    {0x7000, "Additional modules"},
    {0x8000, "Monitoring"},
    {0x9000, "External error"},
    {0xF000, "Additional functions"},
    {0xFF00, "Device specific"},
    {0x0000, "Error reset or no error"},
}};

class Cia402Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "cia402"; }
  std::string message(int v) const override {
    const auto code = static_cast<std::uint16_t>(v);
    return fmt::format("0x{:04X} {}", code, describe(code));
  }
};

}  // namespace

std::string_view describe(std::uint16_t code) noexcept {
  for (const auto& [c, t] : k_exact)
    if (c == code) return t;
  if ((code & 0xFF00) == 0xFF00) return "Device specific";
  for (const auto& [c, t] : k_groups)
    if (c != 0 && (code & 0xF000) == c) return t;
  return "Unknown error code";
}

std::uint8_t error_register_for(std::uint16_t code) noexcept {
  if (code == 0) return 0;
  std::uint8_t r = 0x01;
  switch (code & 0xF000) {
    case 0x2000:
      r |= 0x02;
      break;
    case 0x3000:
      r |= 0x04;
      break;
    case 0x4000:
      r |= 0x08;
      break;
    case 0x8000:
      r |= (code & 0xFF00) == 0x8100 || (code & 0xFF00) == 0x8200 ? 0x10 : 0x20;
      break;
    default:
      break;
  }
  return r;
}

const std::error_category& cia402_category() noexcept {
  static const Cia402Category c;
  return c;
}

}  // namespace hil::cia402
