// SPDX-License-Identifier: MIT
#pragma once
// Text from input files shown in messages: control bytes and bytes that are not UTF-8 become
// `\xNN`, so an error never writes raw binary (or terminal escape sequences) to the terminal.
#include <string>
#include <string_view>

namespace hil {

/// `text` with every byte that is a C0/C1 control (except tab and newline), DEL or not part of
/// valid UTF-8 replaced by `\xNN`.
[[nodiscard]] std::string printable(std::string_view text);

}  // namespace hil
