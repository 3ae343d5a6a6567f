// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_rack.hpp"

#include <fmt/format.h>

namespace hil::controllers::s5 {

std::expected<Ip247Rack, std::string> Ip247Rack::make(const std::vector<Ip247ModuleOptions>& modules) {
  if (modules.empty() || modules.size() > ip247_rack_modules)
    return std::unexpected(fmt::format("{} modules: a rack has 1 to {}", modules.size(), ip247_rack_modules));
  Ip247Rack r;
  for (std::size_t i = 0; i < modules.size(); ++i) {
    const int tile = modules[i].tile;
    if (tile < 0 || tile > 252 || tile % 4 != 0)
      return std::unexpected(fmt::format("tile {}: the SSNR base is a multiple of 4 (0, 4, 8, ... 252)", tile));
    for (std::size_t j = 0; j < i; ++j)
      if (modules[j].tile == tile)
        return std::unexpected(fmt::format("tile {} twice: the modules of a rack have their own SSNR ranges", tile));
    auto p = std::make_unique<Ip247ModulePolicy>(modules[i]);
    Module m;
    m.policy = p.get();
    m.tile = tile;
    if (modules.size() > 1) m.policy->use_plc_blocks(r.plc_.get());
    m.endpoint = std::make_unique<mocks::legacy::S5BlockEndpoint>(std::move(p));
    r.modules_.push_back(std::move(m));
  }
  return r;
}

std::filesystem::path Ip247Rack::state_path(const std::filesystem::path& base, std::size_t i) const {
  if (base.empty() || modules_.size() == 1) return base;
  return base.parent_path() /
         fmt::format("{}-tile{}{}", base.stem().string(), modules_[i].tile, base.extension().string());
}

std::expected<void, std::string> Ip247Rack::load(std::size_t i, const std::string& text) {
  auto& m = modules_[i];
  auto r = m.endpoint->load_state(text);
  m.policy->adopt(m.endpoint->store());
  return r;
}

}  // namespace hil::controllers::s5
