#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Real-time check (issue 18, docs/runtime.md "Measuring a machine"): cyclictest and
# `hilbridge run --realtime` of a scenario, back to back on the same machine at the same period and
# priority: cyclictest, hilbridge, cyclictest again, S seconds each. Prints the wake-up latency
# (mean, p99, max) of each, hilbridge's overruns and skipped cycles, and whether hilbridge's mean
# and p99 are within FACTOR (default 1.2) of cyclictest's (the mean of its two runs), with zero
# overruns. cyclictest's wake-ups a whole period late are printed beside hilbridge's overruns: on a
# machine that stalls the thread for milliseconds, neither can avoid them. Needs root
# (or CAP_SYS_NICE + CAP_IPC_LOCK) and a quiet machine; not part of CI (it takes 3 x S seconds).
#   scripts/rt-compare.sh [--seconds S] [--prio P] [--factor F] [--scenario FILE] [--hilbridge PATH] [--json]
# Exit status: 0 within the factor with zero overruns and skipped cycles, 1 otherwise, 2 on bad use.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=60 prio=80 factor=1.2 scenario=examples/demo.yaml hil=build/hilbridge json=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --prio) prio=$2; shift 2 ;;
    --factor) factor=$2; shift 2 ;;
    --scenario) scenario=$2; shift 2 ;;
    --hilbridge) hil=$2; shift 2 ;;
    --json) json=1; shift ;;
    -h|--help) sed -n '3,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "rt-compare.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
command -v cyclictest >/dev/null || { echo "rt-compare.sh: cyclictest not found (apt-get install rt-tests)" >&2; exit 2; }
[[ -x "$hil" ]] || { echo "rt-compare.sh: $hil not built (bash scripts/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run_cyclictest() {  # NAME: 1 kHz, SCHED_FIFO prio, memory locked, 1 µs histogram to 20 ms
  cyclictest -p"$prio" -i1000 -m -D"$seconds" -q -h 20000 --histfile="$work/$1.hist" >"$work/$1.txt" 2>&1
}
echo "rt-compare: cyclictest -p$prio -i1000 -m -D$seconds ($(uptime | sed 's/.*load/load/'))" >&2
run_cyclictest ct1
echo "rt-compare: $hil run --realtime=$prio --duration ${seconds}s $scenario" >&2
# The scenario's own expectations may not hold when --duration cuts or extends it: only the
# scheduler's figures matter here, so the run's exit status is not checked.
"$hil" run --realtime="$prio" --duration "${seconds}s" -q --json "$scenario" >"$work/hb.json" 2>"$work/hb.err" || true
echo "rt-compare: cyclictest again" >&2
run_cyclictest ct2

python3 - "$work" "$factor" "$json" <<'EOF'
import json, sys
work, factor, as_json = sys.argv[1], float(sys.argv[2]), sys.argv[3] == "1"

def cyclictest(name):
    counts = {}
    for line in open(f"{work}/{name}.hist"):
        if line.startswith("#") or not line.strip():
            continue
        parts = line.split()
        try:
            counts[int(parts[0])] = int(parts[1])
        except (ValueError, IndexError):
            continue
    n = sum(counts.values())
    if n == 0:
        sys.exit(f"rt-compare: cyclictest recorded nothing ({open(f'{work}/{name}.txt').read().strip()})")
    acc, p99, mx = 0, None, max(k for k, v in counts.items() if v)
    for k in sorted(counts):
        acc += counts[k]
        if p99 is None and acc >= 0.99 * n:
            p99 = k
    late = sum(v for k, v in counts.items() if k >= 1000)  # woke a whole period late: hilbridge's overrun
    return {"samples": n, "mean_us": sum(k * v for k, v in counts.items()) / n, "p99_us": p99, "max_us": mx,
            "late_wakeups": late}

try:
    hb = json.load(open(f"{work}/hb.json"))
except (OSError, ValueError):
    sys.exit("rt-compare: hilbridge gave no JSON result:\n" + open(f"{work}/hb.err").read())
s = hb["scheduler"]
lat = s["wake_latency"]
ct = [cyclictest("ct1"), cyclictest("ct2")]
ref = {k: (ct[0][k] + ct[1][k]) / 2 for k in ("mean_us", "p99_us")}
ok = (lat["mean_us"] <= factor * ref["mean_us"] and lat["p99_us"] <= factor * ref["p99_us"]
      and s["overruns"] == 0 and s["skipped_cycles"] == 0)
result = {"cyclictest": ct, "hilbridge": {"samples": lat["samples"], "mean_us": lat["mean_us"], "p99_us": lat["p99_us"],
          "max_us": lat["max_us"], "overruns": s["overruns"], "skipped_cycles": s["skipped_cycles"]},
          "realtime": hb.get("realtime"), "factor": factor, "ok": ok}
if as_json:
    print(json.dumps(result))
else:
    row = "{:<22} {:>9} {:>10.1f} {:>9} {:>9}"
    print("{:<22} {:>9} {:>10} {:>9} {:>9}".format("", "samples", "mean µs", "p99 µs", "max µs"))
    for i, c in enumerate(ct):
        print(row.format(f"cyclictest run {i + 1}", c["samples"], c["mean_us"], c["p99_us"], c["max_us"]))
    print(row.format("hilbridge --realtime", lat["samples"], lat["mean_us"], round(lat["p99_us"]), round(lat["max_us"])))
    print(f"hilbridge: {s['overruns']} overruns, {s['skipped_cycles']} skipped cycles; cyclictest woke a whole "
          f"period late {ct[0]['late_wakeups']} and {ct[1]['late_wakeups']} times (the machine's stalls)")
    print(f"mean {lat['mean_us']:.1f} vs {factor} x {ref['mean_us']:.1f}, p99 {lat['p99_us']:.0f} vs {factor} x {ref['p99_us']:.0f}: "
          + ("within" if ok else "NOT within"))
sys.exit(0 if ok else 1)
EOF
