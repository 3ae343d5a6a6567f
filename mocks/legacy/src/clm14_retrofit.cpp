// SPDX-License-Identifier: MIT
// Retrofit mode of the emulated CLM1.4: machine axes as CLM axes and master encoders.
#include "hil/mocks/legacy/clm14_retrofit.hpp"

#include <fmt/format.h>

namespace hil::mocks::legacy {

std::expected<Clm14MachineRoles, std::string> clm14_machine_roles(std::span<const std::string> names,
                                                                  const std::string& file) {
  Clm14MachineRoles r;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == "ME1" || names[i] == "ME2") {
      auto& e = r.encoders[names[i] == "ME1" ? 0 : 1];
      if (e) return std::unexpected(fmt::format("{}: machine.axes: {} is given twice", file, names[i]));
      e = i;
    } else {
      r.axes.push_back(i);
    }
  }
  if (r.axes.empty() || r.axes.size() > 4)
    return std::unexpected(fmt::format(
        "{}: machine.axes: give 1 to 4 axes (CLM axes 1..4, in IU), besides master encoders named ME1 / ME2", file));
  return r;
}

Clm14Retrofit::Clm14Retrofit(std::span<motion::Axis* const> axes, const Clm14MachineRoles& roles) {
  for (const std::size_t i : roles.axes)
    ports_.push_back(std::make_unique<controllers::clm14::MotionAxisPort>(*axes[i]));
  for (std::size_t k = 0; k < 2; ++k)
    if (roles.encoders[k])
      encoders_[k] = std::make_unique<controllers::clm14::MotionMasterEncoder>(*axes[*roles.encoders[k]]);
}

void Clm14Retrofit::attach(Clm14Station& station, std::function<void(const CycleTime&)> update) {
  std::array<controllers::clm14::AxisPort*, 4> ports{};
  for (std::size_t i = 0; i < ports_.size() && i < 4; ++i) ports[i] = ports_[i].get();
  station.use_axes(ports, std::move(update));
  for (int k = 1; k <= 2; ++k)
    if (encoders_[static_cast<std::size_t>(k - 1)])
      station.use_master_encoder(k, encoders_[static_cast<std::size_t>(k - 1)].get());
}

}  // namespace hil::mocks::legacy
