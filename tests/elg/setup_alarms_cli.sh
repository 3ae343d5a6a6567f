#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The setting-up modes' alarms raised by their conditions through the controller's panel inputs in
# a scenario: 2035 (rapid JOG above MD 280*) and 184* (REF stopped behind the cam).
#   setup_alarms_cli.sh HILBRIDGE SOURCE_DIR
set -euo pipefail
cd "$2/tests/elg/data"
"$1" test elg-2035.yaml elg-184.yaml
