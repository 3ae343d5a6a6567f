// SPDX-License-Identifier: MIT
#include "hil/core/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

namespace hil {

namespace {
const char* kind_of(mode_t m) {
  if (S_ISDIR(m)) return "a directory";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a plain file";
}
}  // namespace

std::expected<std::string, std::string> read_text_file(const std::filesystem::path& path, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO with no writer must not hang; it is refused below anyway.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::unexpected(fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  struct stat st {};
  std::string error;
  if (::fstat(fd, &st) != 0) {
    error = fmt::format("cannot read {}: {}", path.string(), std::strerror(errno));
  } else if (!S_ISREG(st.st_mode)) {
    error = fmt::format("{} is not a regular file ({}): give a file", path.string(), kind_of(st.st_mode));
  } else if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    error = fmt::format("{} is {} bytes; input files are limited to {} bytes ({} MiB)", path.string(), st.st_size,
                        max_bytes, max_bytes >> 20);
  }
  std::string text;
  if (error.empty()) {
    text.resize(static_cast<std::size_t>(st.st_size));
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        error = fmt::format("cannot read {}: {}", path.string(), std::strerror(errno));
        break;
      }
      if (n == 0) break;  // shrank while reading
      done += static_cast<std::size_t>(n);
    }
    text.resize(done);
  }
  ::close(fd);
  if (!error.empty()) return std::unexpected(error);
  return text;
}

}  // namespace hil
