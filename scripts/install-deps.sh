#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install hilbridge's build and test dependencies from Debian 12 packages. Idempotent: only
# missing packages are installed, and apt-get update runs only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache clang-format
  # cpack -G DEB: dpkg-shlibdeps computes the package's dependencies
  dpkg-dev file
  libasio-dev libyaml-cpp-dev libcli11-dev libfmt-dev libspdlog-dev nlohmann-json3-dev
  libmodbus-dev libgpiod-dev gpiod
  libgtest-dev libgmock-dev libbenchmark-dev
  # coverage-guided fuzzing (scripts/fuzz.sh): clang 16 and its libFuzzer (with libstdc++, the
  # standard library Debian's yaml-cpp and fmt are built against: see CMakeLists.txt)
  clang-16 libfuzzer-16-dev
  # independent peers for interop tests
  can-utils python3 python3-can python3-pymodbus python3-serial python3-serial-asyncio mbpoll socat tshark
)
if [[ "${1:-}" == "--with-vm" ]]; then
  # real-kernel tests (tests/vm/run-in-kernel.sh adds the kernel packages itself)
  packages+=(qemu-system-x86 busybox-static cpio kmod xz-utils)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO=sudo; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
