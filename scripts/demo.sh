#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 1: install what is missing, build hilbridge, and run the bundled demo
# (examples/demo.yaml: three axes on simulated drives, about 8 s, live status and a summary).
# Extra arguments go to `hilbridge run`, e.g. `bash scripts/demo.sh --plot demo.svg`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
HIL_TARGETS=hilbridge bash scripts/build.sh
exec ./build/hilbridge run "$@"
