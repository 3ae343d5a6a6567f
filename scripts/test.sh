#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2 (and .ci/run): install what is missing, check formatting, build with warnings as
# errors (build/), run the whole host suite, build once more with AddressSanitizer + UBSan (preset
# `asan`: -O1 -g1, build-asan/) and run the whole host suite there, build the threaded parts with
# ThreadSanitizer and run their tests (scripts/tsan.sh), then the `kernel`-labelled tests inside a VM
# with Debian's real kernel (vcan, gpio-sim). Exits non-zero if anything blocking fails; every stage
# runs even when an earlier one failed, and the time of each is printed at the end.
#
# The sanitizer stages are advisory (reported in the table, not failing the run) until the ASan host
# suite has run green end to end on the merged tree; HIL_CI_STRICT=1 makes them blocking. The plan
# then is one instrumented build for everything (docs/reliability.md, "CI"). HIL_CI_ASAN=0 /
# HIL_CI_TSAN=0 skip those stages; HIL_CI_FULL=1 adds every fuzz target coverage-guided for
# $HIL_FUZZ_SECONDS (default 3) seconds (clang-16, build-fuzz/).
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

# advisory NAME CMD...: like stage, but a failure is reported without failing the run;
# HIL_CI_STRICT=1 makes it blocking.
advisory() {
  if [[ "${HIL_CI_STRICT:-0}" == 1 ]]; then stage "$@"; return 0; fi
  local name=$1 t0=$SECONDS rc=0
  shift
  echo "== $name (advisory)"
  "$@" || rc=$?
  timings+=("$(printf '%-34s %4ds %s' "$name" $((SECONDS - t0)) "$([[ $rc -eq 0 ]] && echo ok || echo "FAILED ($rc), advisory")")")
  return 0
}

stage "format (clang-format --dry-run)" bash scripts/check-format.sh
stage "build (-Werror)" bash scripts/build.sh -DHIL_WERROR=ON -DHIL_BUILD_TESTS=ON -DHIL_BUILD_BENCH=ON "${launcher[@]}"
stage "host suite" ctest --test-dir build --output-on-failure -j"$(nproc)" -LE kernel --no-tests=error
if [[ "${HIL_CI_ASAN:-1}" != 0 ]]; then
  asan_build() {
    cmake --preset asan "${launcher[@]}" >/dev/null && cmake --build --preset asan -j"$(nproc)"
  }
  advisory "asan+ubsan build" asan_build
  advisory "asan+ubsan host suite" ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE kernel \
    --no-tests=error
fi
if [[ "${HIL_CI_TSAN:-1}" != 0 ]]; then
  # ThreadSanitizer on the threaded parts only (Modbus worker and server, socketcand hub and
  # client, edge writer, serial emulator host): build-tsan/, their test programs, their tests.
  advisory "tsan (threaded parts)" bash scripts/tsan.sh
fi
if [[ -x tests/vm/run-in-kernel.sh ]]; then
  stage "kernel tests (VM)" tests/vm/run-in-kernel.sh -- ctest --test-dir build --output-on-failure -L kernel \
    --no-tests=error
fi
if [[ "${HIL_CI_FULL:-0}" == 1 ]]; then
  # Coverage-guided fuzzing after the replays above (docs/reliability.md); the repository's corpus
  # is left as it is.
  stage "coverage-guided fuzzing" bash scripts/fuzz.sh --seconds "${HIL_FUZZ_SECONDS:-3}" --no-keep
fi
printf '\n%s\n' "${timings[@]}"
printf '%-34s %4ds\n' "total" "$SECONDS"
exit $status
