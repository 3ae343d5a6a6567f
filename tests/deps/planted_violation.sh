#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The dependency-rules check must fail on a broken rule: copies the checked areas and
# docs/ARCHITECTURE.md, plants two violations (the core including the runtime, yaml-cpp in the pure
# CiA 402 codec) and expects exit status 1 naming both, then 0 once they are taken out again.
# Usage: planted_violation.sh SOURCE_DIR
set -euo pipefail
src=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/hil-deps.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/docs" "$work/scripts"
cp -r "$src/bridge" "$src/protocols" "$src/drives" "$src/profiles" "$src/mocks" "$work/"
cp "$src/docs/ARCHITECTURE.md" "$work/docs/"
cp "$src/scripts/check_dependencies.py" "$work/scripts/"

python3 "$work/scripts/check_dependencies.py" --root "$work" >/dev/null  # the copy passes as is

core=$work/bridge/core/src/fault.cpp codec=$work/protocols/cia402/src/cia402.cpp
cp "$core" "$work/core.orig"
cp "$codec" "$work/codec.orig"
echo '#include "hil/runtime/runner.hpp"' >>"$core"
echo '#include <yaml-cpp/yaml.h>' >>"$codec"
status=0
python3 "$work/scripts/check_dependencies.py" --root "$work" >"$work/out" || status=$?
cat "$work/out"
[[ $status -eq 1 ]] || { echo "expected exit status 1, got $status"; exit 1; }
grep -q 'bridge/core/src/fault.cpp:.*area bridge/core includes hil/runtime/runner.hpp of area bridge/runtime' "$work/out"
grep -q 'protocols/cia402/src/cia402.cpp:.*area protocols/cia402 uses yaml-cpp' "$work/out"

cp "$work/core.orig" "$core"
cp "$work/codec.orig" "$codec"
python3 "$work/scripts/check_dependencies.py" --root "$work" >/dev/null
echo "planted violations found; clean copy passes"
