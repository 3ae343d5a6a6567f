// SPDX-License-Identifier: MIT
#include "hil/modbus/exchange_plan.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace hil::modbus {
namespace {

std::vector<RegisterBlock> group(const Profile& p, bool command, bool single_registers) {
  std::vector<RegisterBlock> ranges;
  for (std::size_t i = 0; i < kFieldRoleCount; ++i) {
    const auto role = static_cast<FieldRole>(i);
    const RegisterField& f = p.fields[i];
    if (!f.present || is_command(role) != command) continue;
    ranges.push_back({p.space_of(role), f.address, f.words()});
  }
  std::sort(ranges.begin(), ranges.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (single_registers) {
    std::vector<RegisterBlock> out;
    for (const auto& r : ranges)
      for (std::uint16_t k = 0; k < r.count; ++k) out.push_back({r.space, static_cast<std::uint16_t>(r.first + k), 1});
    return out;
  }
  std::vector<RegisterBlock> out;
  const std::uint16_t limit = command ? kMaxWriteRegisters : kMaxReadRegisters;
  for (const auto& r : ranges) {
    if (!out.empty() && std::uint32_t{out.back().first} + out.back().count == r.first &&
        out.back().count + r.count <= limit) {
      out.back().count = static_cast<std::uint16_t>(out.back().count + r.count);
    } else {
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace

std::expected<ExchangePlan, std::string> make_exchange_plan(const Profile& profile) {
  ExchangePlan plan;
  plan.write_fc = profile.function_codes.write;
  plan.read_fc = profile.function_codes.read;
  plan.writes = group(profile, true, plan.write_fc == 6);
  plan.reads = group(profile, false, false);
  if (profile.function_codes.read_write) {
    if (plan.read_fc != 3)
      return std::unexpected(std::string("FC 23 reads holding registers: set function_codes.read to 3"));
    if (plan.writes.size() != 1 || plan.reads.size() != 1)
      return std::unexpected(
          fmt::format("FC 23 needs the command fields in one contiguous block and the feedback fields in another "
                      "(got {} command and {} feedback blocks); move the registers or drop read_write",
                      plan.writes.size(), plan.reads.size()));
    if (plan.writes[0].count > kMaxRwWriteRegisters)
      return std::unexpected(fmt::format("FC 23 writes at most {} registers", kMaxRwWriteRegisters));
    plan.read_write = true;
  }
  return plan;
}

}  // namespace hil::modbus
