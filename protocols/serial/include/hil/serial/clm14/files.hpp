// SPDX-License-Identifier: MIT
#pragma once
// The text files a technician keeps for a CLM1.4 (one item per line, as the device lists it):
//   program:    "NNNN MNEMONIC operands"        e.g. "0101 AEA Q1.00.3 1"
//   parameters: "NUMBER data"                   e.g. "B002 019200 0 1 8 1"
// ';' starts a comment line. Field spacing inside the data is kept exactly (fixed widths).
// Pure: text in, items or a list of every problem (file:line: what) out. Validation uses the
// device profile through DeviceData, so an invalid file is rejected before anything is sent.

#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/serial/clm14/device_data.hpp"

namespace hil::serial::clm14 {

enum class FileKind { program, parameters };

struct FileItem {
  std::string key;      ///< "0101" (program line) or "B002" (parameter number)
  std::string text;     ///< "AEA Q1.00.3 1" / "019200 0 1 8 1" (no trailing spaces)
  int source_line = 0;  ///< 1-based line in the file (0 when not from a file)
  friend bool operator==(const FileItem& a, const FileItem& b) { return a.key == b.key && a.text == b.text; }
};

struct DeviceFile {
  FileKind kind = FileKind::program;
  std::vector<FileItem> items;  ///< in file order
};

/// "file:line: message" for every problem found (all of them, not just the first).
using FileProblems = std::vector<std::string>;

/// Parse and validate a file. `axes` limits the A-parameters (A1xx..A4xx). `name` appears in messages.
[[nodiscard]] std::expected<DeviceFile, FileProblems> parse_device_file(std::string_view text, FileKind kind,
                                                                        const DeviceData& data, int axes,
                                                                        std::string_view name);
/// Text of a file (header comment + one item per line), the inverse of parse_device_file.
[[nodiscard]] std::string make_device_file(const DeviceFile& file, std::string_view header_comment);

/// Parse "program"/"parameters" (also "params").
[[nodiscard]] std::expected<FileKind, std::string> parse_file_kind(std::string_view s);

}  // namespace hil::serial::clm14
