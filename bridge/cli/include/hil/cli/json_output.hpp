// SPDX-License-Identifier: MIT
#pragma once
// `--json` output of the CLI commands (docs/json.md): one JSON object per command on stdout,
// everything meant for a person (live status, progress, messages) on stderr. An error under
// --json is an object with an "error" member on stdout *and* the usual message on stderr; the
// exit status is the same as without --json (0 ok, 1 the checked thing failed, 2 usage or
// configuration). Thread: the command's (main) thread; blocking stdio.

#include <cstdio>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace hil::cli {

/// `j` on one line followed by '\n' on `out` (stdout by default), flushed. Invalid UTF-8 in
/// strings is replaced (U+FFFD), never an exception.
void print_json(const nlohmann::json& j, std::FILE* out = stdout);

/// The error convention of every command: `message` (one line, no "error: " prefix) on stderr
/// prefixed by `prefix` ("hilbridge modbus: ", "error: "), and under `json` also
/// {"error": message, ...extra} on stdout. Returns `exit_code` so a command can
/// `return report_error(...)`.
int report_error(bool json, std::string_view prefix, const std::string& message, int exit_code,
                 nlohmann::json extra = nlohmann::json::object());

/// Lower-case hex of `data` without separators ("0a11ff"); "" for no bytes.
[[nodiscard]] std::string hex_bytes(const unsigned char* data, std::size_t size);

}  // namespace hil::cli
