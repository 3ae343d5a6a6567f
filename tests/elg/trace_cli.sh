#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The ELG's C-against-linkage value in a run's trace and plot: `hilbridge run --trace --plot` of the
# shipped annex example has the column ctl_C_linkage_error_deg, non-zero while coupled (C's
# following error), inside C's 1 deg window, zero while uncoupled; the SVG has its chart.
#   trace_cli.sh HILBRIDGE SOURCE_DIR
set -euo pipefail
hil=$1
cd "$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$hil" run --virtual -q --trace "$work/t.csv" --plot "$work/p.svg" examples/controllers/elg.yaml >/dev/null
grep -q 'controller: C linkage error \[deg\]' "$work/p.svg" || { echo "FAIL: no linkage chart in the plot"; exit 1; }
/usr/bin/python3 - "$work/t.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
col = "ctl_C_linkage_error_deg"
assert col in rows[0], f"no column {col}: {list(rows[0])}"
coupled = [abs(float(r[col])) for r in rows if r["io_coupled"] == "1"]
free = [abs(float(r[col])) for r in rows if r["io_coupled"] == "0"]
assert coupled and max(coupled) > 0.0, "zero while coupled"
assert max(coupled) < 1.0, f"C off the linkage by {max(coupled)} deg"
assert max(free) == 0.0, "non-zero while uncoupled"
print(f"ok: {len(coupled)} coupled rows, C within {max(coupled):.4f} deg of the linkage")
PY
