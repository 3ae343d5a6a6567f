// SPDX-License-Identifier: MIT
#include "hil/core/text_file.hpp"

#include <fstream>
#include <system_error>

namespace hil {

namespace {
const char* kind_of(std::filesystem::file_type t) {
  switch (t) {
    case std::filesystem::file_type::directory:
      return "a directory";
    case std::filesystem::file_type::fifo:
      return "a FIFO";
    case std::filesystem::file_type::character:
      return "a character device";
    case std::filesystem::file_type::block:
      return "a block device";
    case std::filesystem::file_type::socket:
      return "a socket";
    default:
      return "not a plain file";
  }
}
}  // namespace

std::expected<std::string, std::string> read_text_file(const std::filesystem::path& path, std::size_t max_bytes) {
  // The kind is checked before the file is opened: opening a FIFO with no writer would block.
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec) return std::unexpected("cannot open " + path.string() + ": " + ec.message());
  if (!std::filesystem::is_regular_file(st)) {
    return std::unexpected(path.string() + " is not a regular file (" + kind_of(st.type()) + "): give a file");
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) return std::unexpected("cannot read " + path.string() + ": " + ec.message());
  if (size > max_bytes) {
    return std::unexpected(path.string() + " is " + std::to_string(size) + " bytes; input files are limited to " +
                           std::to_string(max_bytes) + " bytes (" + std::to_string(max_bytes >> 20) + " MiB)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::unexpected("cannot open " + path.string());
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) return std::unexpected("cannot read " + path.string());
  text.resize(static_cast<std::size_t>(in.gcount()));  // a file that shrank while reading
  return text;
}

}  // namespace hil
