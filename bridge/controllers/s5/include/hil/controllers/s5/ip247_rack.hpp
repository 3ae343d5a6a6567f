// SPDX-License-Identifier: MIT
#pragma once
// A rack of IP247 modules behind `hilbridge emulate ip247` (docs/ip247.md, "Several modules on the
// line"): one Ip247ModulePolicy and one RK512 data-block endpoint per module, each served on its own
// line (the module's mapping of DB n / DX 1..4 unchanged), every module with its own SSNR base
// (tile), program memory, MD images and state file; the PLC's DBs of the data jobs (DX 5..255) are
// one PLC's and shared by the modules. Thread: the endpoint host's (all lines on one thread).

#include <cstddef>
#include <expected>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hil/controllers/s5/ip247_module_endpoint.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_rack_modules = 8;  ///< at most (as the runtime's modules per block)

class Ip247Rack {
 public:
  /// One module per entry, in order; the tiles (SSNR bases) must be distinct multiples of 4.
  [[nodiscard]] static std::expected<Ip247Rack, std::string> make(const std::vector<Ip247ModuleOptions>& modules);

  [[nodiscard]] std::size_t size() const noexcept { return modules_.size(); }
  [[nodiscard]] Ip247ModulePolicy& policy(std::size_t i) noexcept { return *modules_[i].policy; }
  [[nodiscard]] mocks::legacy::S5BlockEndpoint& endpoint(std::size_t i) noexcept { return *modules_[i].endpoint; }
  [[nodiscard]] int tile(std::size_t i) const noexcept { return modules_[i].tile; }
  /// The PLC's DBs shared by the modules (with one module: the module's own).
  [[nodiscard]] const S5Blocks& plc_blocks() const noexcept { return modules_.front().policy->plc_blocks(); }

  /// The state file of module i from the device's `base` path: `base` itself for a single module,
  /// else `<stem>-tile<T><ext>` next to it (a module keeps its images whatever the order).
  [[nodiscard]] std::filesystem::path state_path(const std::filesystem::path& base, std::size_t i) const;
  /// Loads module i's saved state text (its images) into its endpoint and the module (battery-backed
  /// MD and programs). A text that does not load is the error; the module starts empty then.
  std::expected<void, std::string> load(std::size_t i, const std::string& text);

 private:
  struct Module {
    Ip247ModulePolicy* policy = nullptr;
    std::unique_ptr<mocks::legacy::S5BlockEndpoint> endpoint;
    int tile = 0;
  };
  std::unique_ptr<S5Blocks> plc_ = std::make_unique<S5Blocks>();
  std::vector<Module> modules_;
};

}  // namespace hil::controllers::s5
