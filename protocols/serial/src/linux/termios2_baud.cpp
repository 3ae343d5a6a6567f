// SPDX-License-Identifier: MIT
// termios2 (BOTHER) lives in <asm/termbits.h>, which cannot share a translation unit with
// glibc's <termios.h>; this file holds only the custom-baud ioctl.
#include <asm/ioctls.h>
#include <asm/termbits.h>

#include <cerrno>

extern "C" int ioctl(int fd, unsigned long request, ...) noexcept;

namespace hil::serial::linux_io {

/// Set input and output speed of `fd` to exactly `baud` bit/s. Returns 0 or errno.
int set_any_baud(int fd, unsigned baud) noexcept {
  struct termios2 t {};
  if (ioctl(fd, TCGETS2, &t) != 0) return errno;
  t.c_cflag &= ~static_cast<tcflag_t>(CBAUD | (CBAUD << IBSHIFT));
  t.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
  t.c_ispeed = baud;
  t.c_ospeed = baud;
  if (ioctl(fd, TCSETS2, &t) != 0) return errno;
  return 0;
}

}  // namespace hil::serial::linux_io
