// SPDX-License-Identifier: MIT
#pragma once
// The axes of one WF 725/726 module (docs/wf725.md, "Several axes" and "Combined programs"):
// up to three Wf725Controller axes (letters A, B, C) that share one program memory and know each
// other, so that a combined program started on one axis (the master) moves the others (slaves):
// blocks with another axis' letter, G17/G18/G19 interpolation pairs. `hilbridge emulate wf725`
// and the scenario controller of a WF 726 with several axes (Wf726ModuleController) both hold one.
// The module does not own its axes, and its axes keep a pointer to it: no axis cycles after the
// module is gone (its holder destroys or detaches them together). Further couplings
// between two axes of the module (split drive MD 27) are added here, as calls on the pair.
// Thread: the module's cycle thread (the axes' controller cycles).

#include <array>
#include <cstddef>
#include <expected>
#include <string>
#include <vector>

namespace hil::controllers::s5 {

class Wf725Controller;

class Wf726Module {
 public:
  Wf726Module() = default;
  ~Wf726Module() = default;
  Wf726Module(const Wf726Module&) = delete;
  Wf726Module& operator=(const Wf726Module&) = delete;

  /// Adds `axis` (non-null) under its letter: it joins the module's program memory (the first
  /// axis' memory) and may be master or slave of combined programs. Error text when the letter is
  /// taken or the module has three axes already.
  std::expected<void, std::string> add(Wf725Controller& axis);
  /// The axis with letter `letter` ('A'..'C'), nullptr when the module has none.
  [[nodiscard]] Wf725Controller* axis(char letter) const noexcept;
  /// The axes in the order they were added.
  [[nodiscard]] const std::vector<Wf725Controller*>& axes() const noexcept { return axes_; }
  [[nodiscard]] std::size_t size() const noexcept { return axes_.size(); }

 private:
  std::vector<Wf725Controller*> axes_;
  std::array<Wf725Controller*, 3> by_letter_{};
};

}  // namespace hil::controllers::s5
