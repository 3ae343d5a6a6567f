// SPDX-License-Identifier: MIT
// The axes of one WF 726 module (docs/wf725.md, "Combined programs").
#include "hil/controllers/s5/wf726_module.hpp"

#include <fmt/format.h>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {

std::expected<void, std::string> Wf726Module::add(Wf725Controller& axis) {
  const char letter = axis.axis_letter();
  if (letter < 'A' || letter > 'C') return std::unexpected(fmt::format("axis letter '{}': A, B or C", letter));
  auto& slot = by_letter_[static_cast<std::size_t>(letter - 'A')];
  if (slot != nullptr) return std::unexpected(fmt::format("the module has an axis {} already", letter));
  if (axes_.size() >= 3) return std::unexpected("a WF 726 has at most three axes (A, B, C)");
  if (!axes_.empty()) axis.use_program_store(axes_.front()->program_store());
  slot = &axis;
  axes_.push_back(&axis);
  axis.join_module(this);
  return {};
}

Wf725Controller* Wf726Module::axis(char letter) const noexcept {
  if (letter < 'A' || letter > 'C') return nullptr;
  return by_letter_[static_cast<std::size_t>(letter - 'A')];
}

}  // namespace hil::controllers::s5
