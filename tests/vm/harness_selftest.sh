#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Self-test of tests/vm/run-in-kernel.sh: a failing command, a deliberately failing kernel test,
# a VM that never reports and a timeout must each give their own, distinct exit status, so that
# .ci/run cannot go green over a broken kernel test. Boots the VM four times (about 40 s warm).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
harness=$here/run-in-kernel.sh
if [[ $(id -u) -ne 0 ]] || ! command -v qemu-system-x86_64 >/dev/null; then
  echo "SKIP: needs root and qemu-system-x86 (scripts/install-deps.sh --with-vm installs it)"
  exit 77
fi
work=$(mktemp -d -p "${HIL_SELFTEST_DIR:-$PWD}")
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
expect() {  # expect STATUS DESCRIPTION -- CMD...
  local want=$1 what=$2
  shift 3
  local got
  HIL_VM_LOG=$work/console.log "$@" >"$work/out.txt" 2>&1
  got=$?
  if [[ $got -eq $want ]]; then
    echo "ok: $what -> $got"
  else
    echo "FAIL: $what: expected exit $want, got $got"
    tail -20 "$work/out.txt"
    failures=$((failures + 1))
  fi
}
expect 3 "command status passes through" -- "$harness" -- sh -c 'exit 3'

# A deliberately failing kernel-labelled test: ctest inside the VM fails, so the harness does.
mkdir -p "$work/ctest"
cat > "$work/ctest/CTestTestfile.cmake" <<'CT'
add_test(deliberately_failing_kernel_test "/bin/sh" "-c" "test -d /sys/class/net/vcan0 && exit 1")
set_tests_properties(deliberately_failing_kernel_test PROPERTIES LABELS "kernel")
CT
expect 8 "a failing kernel test fails the run (ctest status 8)" -- "$harness" -- ctest --test-dir "$work/ctest" -L kernel
expect 125 "a VM whose setup fails never reports" -- env HIL_VM_VCAN=an-interface-name-far-too-long "$harness" -- true
expect 124 "a hung command times out" -- env HIL_VM_TIMEOUT=30 "$harness" -- sleep 600
((failures == 0)) && echo "harness self-test: all 4 cases passed"
exit $((failures > 0))
