#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2 (and .ci/run): install what is missing, check formatting, build the tree ONCE with
# AddressSanitizer + UBSan's arithmetic, bounds and enum checks at -Og, warnings as errors, libraries
# and CLI modules as unity batches (preset `ci`, build-ci/), run the whole host suite on it, then the `kernel`-labelled tests of the same build inside
# a VM with Debian's real kernel (vcan, gpio-sim). Exits non-zero if anything fails; every stage runs
# even when an earlier one failed, and the time of each is printed at the end.
#
# One build, because a cold build of this tree is most of CI's 20-minute budget on two cores
# (docs/reliability.md, "CI"). HIL_CI_FULL=1 adds, before a release: the plain -O2 build (build/,
# the one the demo and the benchmarks use) with its host suite, the `asan` preset (every UBSan
# check, -O1 -g1) with its host suite, ThreadSanitizer on the threaded parts (scripts/tsan.sh) and
# every fuzz target coverage-guided for $HIL_FUZZ_SECONDS (default 3) seconds (clang-16,
# build-fuzz/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --with-vm

# ccache makes the second and later runs on one machine rebuild only what changed, for every build.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
status=0 timings=()
stage() {  # stage NAME CMD...: runs CMD, records its time, keeps going on failure
  local name=$1 t0=$SECONDS rc=0
  shift
  echo "== $name"
  "$@" || rc=$?
  timings+=("$(printf '%-34s %4ds %s' "$name" $((SECONDS - t0)) "$([[ $rc -eq 0 ]] && echo ok || echo "FAILED ($rc)")")")
  if [[ $rc -ne 0 ]]; then status=1; fi
  return 0
}

stage "format (clang-format --dry-run)" bash scripts/check-format.sh
ci_build() {
  cmake --preset ci "${launcher[@]}" >/dev/null && cmake --build --preset ci -j"$(nproc)"
}
stage "build (ci: ASan+UBSan -Og, -Werror)" ci_build
# LeakSanitizer runs at every test program's exit; a report fails that test with its output. It
# stops the process with ptrace: where a container forbids that, every program would fail at exit,
# so leak checking is turned off there (and said so) while ASan and UBSan keep checking.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
if [[ -x build-ci/hilbridge ]] && build-ci/hilbridge --version 2>&1 | grep -q "LeakSanitizer has encountered a fatal error"; then
  echo "note: LeakSanitizer cannot run here (ptrace refused); leak checks off, ASan and UBSan on"
  export ASAN_OPTIONS=detect_leaks=0
fi
# Label `long` (the million-case replanning reference sweep, 80 s under ASan) runs in the plain
# build's suite of HIL_CI_FULL=1; the seeded reference sweeps of the same planner run here.
stage "host suite (build-ci)" ctest --test-dir build-ci --output-on-failure -j"$(nproc)" -LE "kernel|long" \
  --no-tests=error
if [[ -x tests/vm/run-in-kernel.sh ]]; then
  stage "kernel tests (VM, build-ci)" tests/vm/run-in-kernel.sh -- ctest --test-dir build-ci --output-on-failure \
    -L kernel --no-tests=error
fi
if [[ "${HIL_CI_FULL:-0}" == 1 ]]; then
  stage "plain build (-O2, -Werror)" bash scripts/build.sh -DHIL_WERROR=ON -DHIL_BUILD_TESTS=ON -DHIL_BUILD_BENCH=ON \
    "${launcher[@]}"
  stage "host suite (build)" ctest --test-dir build --output-on-failure -j"$(nproc)" -LE kernel --no-tests=error
  asan_build() {
    cmake --preset asan "${launcher[@]}" >/dev/null && cmake --build --preset asan -j"$(nproc)"
  }
  stage "asan build (every UBSan check)" asan_build
  stage "host suite (build-asan)" ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE kernel \
    --no-tests=error
  # ThreadSanitizer on the threaded parts only (Modbus worker and server, socketcand hub and
  # client, edge writer, serial emulator host): build-tsan/, their test programs, their tests.
  stage "tsan (threaded parts)" bash scripts/tsan.sh
  # Coverage-guided fuzzing after the replays above (docs/reliability.md); the repository's corpus
  # is left as it is.
  stage "coverage-guided fuzzing" bash scripts/fuzz.sh --seconds "${HIL_FUZZ_SECONDS:-3}" --no-keep
fi
printf '\n%s\n' "${timings[@]}"
printf '%-34s %4ds\n' "total" "$SECONDS"
exit $status
