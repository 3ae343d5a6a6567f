// SPDX-License-Identifier: MIT
#pragma once
// Internal: the std::visit helper of the runtime (a lambda per alternative).

namespace hil::runtime::detail {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
// Deduction guide: clang 16 (the fuzzing build) has no CTAD for aggregates yet.
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace hil::runtime::detail
