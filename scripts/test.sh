#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2 (and .ci/run): install what is missing, build with warnings as errors,
# run the whole test suite on the host, then the `kernel`-labelled tests inside a VM with
# Debian's real kernel (vcan, gpio-sim). Exits non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --with-vm
bash scripts/build.sh -DHIL_WERROR=ON -DHIL_BUILD_TESTS=ON -DHIL_BUILD_BENCH=ON
status=0
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE kernel --no-tests=error || status=$?
# Coverage-guided fuzzing after the replay above: every target for a few seconds under ASan + UBSan
# (clang-16, build-fuzz/; docs/reliability.md). The corpus in the repository is left as it is.
bash scripts/fuzz.sh --seconds "${HIL_FUZZ_SECONDS:-3}" --no-keep || status=$?
if [[ -x tests/vm/run-in-kernel.sh ]]; then
  tests/vm/run-in-kernel.sh -- ctest --test-dir build --output-on-failure -L kernel --no-tests=error || status=$?
fi
exit $status
