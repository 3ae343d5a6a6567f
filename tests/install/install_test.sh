#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the build tree into a scratch prefix, builds a consumer project against it (CMake
# package and pkg-config), then moves the prefix and runs the installed hilbridge from there:
# the data (examples, Modbus and device profiles) must come from the moved tree.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 src=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/hil-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
p=$work/p q=$work/q

step() { printf '\n== %s\n' "$*"; }

step "cmake --install $build --prefix $p"
cmake --install "$build" --prefix "$p" >/dev/null
for f in bin/hilbridge share/hilbridge/examples/demo.yaml share/hilbridge/examples/modbus-demo.yaml \
  share/hilbridge/profiles/modbus/cia402.yaml share/hilbridge/profiles/devices/clm14.yaml \
  share/hilbridge/profiles/canopen/hil_cia402_drive.eds include/hil/core/drive.hpp \
  lib/cmake/hilbridge/hilbridgeConfig.cmake lib/pkgconfig/hilbridge.pc lib/libhil_core.a; do
  [[ -e $p/$f ]] || { echo "missing in the installed tree: $f"; exit 1; }
done

# An ASan + UBSan build (CI's, preset `asan`) installs instrumented static libraries: a consumer
# links them with the sanitizer runtime, as any user of that tree would have to.
san=()
if grep -q '^HIL_SANITIZE:BOOL=ON' "$build/CMakeCache.txt"; then san=(-fsanitize=address,undefined); fi

step "consumer project: find_package(hilbridge)"
generator=()
if command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S "$src/tests/install/consumer" -B "$work/consumer" "${generator[@]}" -DCMAKE_PREFIX_PATH="$p" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS="${san[*]}" >/dev/null
cmake --build "$work/consumer" >/dev/null
"$work/consumer/consumer" "$p/share/hilbridge"

step "consumer through pkg-config"
export PKG_CONFIG_PATH=$p/lib/pkgconfig
# shellcheck disable=SC2046
g++ "${san[@]}" $(pkg-config --cflags hilbridge) "$src/tests/install/consumer/main.cpp" -o "$work/consumer_pc" \
  $(pkg-config --libs hilbridge)
"$work/consumer_pc" "$p/share/hilbridge"

step "relocated prefix: mv $p $q"
mv "$p" "$q"
cd "$work"  # no ./examples here: the demo must come from the installed tree
"$q/bin/hilbridge" --version
"$q/bin/hilbridge" run --virtual >"$work/demo.out" || { cat "$work/demo.out"; exit 1; }
"$q/bin/hilbridge" run "$q/share/hilbridge/examples/modbus-demo.yaml" --virtual >"$work/modbus.out" ||
  { cat "$work/modbus.out"; exit 1; }
# A Modbus profile that exists only in the moved tree: found by name, so the lookup is relative to
# the executable, not to the source tree the binary was built from.
cp "$q/share/hilbridge/profiles/modbus/cia402.yaml" "$q/share/hilbridge/profiles/modbus/only_in_q.yaml"
sed 's/profile: cia402 /profile: only_in_q /' "$q/share/hilbridge/examples/modbus-demo.yaml" >"$work/only_in_q.yaml"
grep -q 'profile: only_in_q' "$work/only_in_q.yaml"
"$q/bin/hilbridge" run "$work/only_in_q.yaml" --virtual >"$work/only.out" || { cat "$work/only.out"; exit 1; }
"$work/consumer/consumer" "$q/share/hilbridge"
echo "install test: ok"
