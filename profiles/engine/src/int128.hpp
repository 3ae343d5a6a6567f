// SPDX-License-Identifier: MIT
#pragma once
// 128-bit intermediates for exact decimal arithmetic (GCC/Clang extension, marked as such so
// -Wpedantic stays quiet).
namespace hil::profiles::detail {
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;
}  // namespace hil::profiles::detail
