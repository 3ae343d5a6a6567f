#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 1: install what is missing, build, and run the bundled demo
# (examples/demo.yaml on simulated drives). Extra arguments go to `hilbridge run`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh -DHIL_BUILD_BENCH=OFF
exec ./build/hilbridge run "$@"
