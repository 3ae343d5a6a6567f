#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hilbridge latency from the command line (usage: latency_cli.sh HILBRIDGE): text output with the
# histogram and the recommendation, --json through python3 -m json.tool and its content, bad
# options exit 2, and (as root) the real-time path under --load (exit 77 = skipped when SCHED_FIFO
# is refused; the unprivileged part has then still run).
set -u
hb=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$hb" latency --duration 300ms --period 1ms >"$tmp/text" 2>&1 || fail "latency exited $?: $(cat "$tmp/text")"
for want in "wake-up latency: min" "overruns: " "recommended minimum cycle period:" " us - "; do
  grep -qF -- "$want" "$tmp/text" || fail "text output lacks '$want': $(cat "$tmp/text")"
done
echo "ok: text output"; cat "$tmp/text"

"$hb" latency --duration 300ms --period 500us --json >"$tmp/j.json" 2>"$tmp/err" || fail "--json exited $?: $(cat "$tmp/err")"
python3 -m json.tool "$tmp/j.json" >/dev/null || fail "--json does not parse: $(cat "$tmp/j.json")"
python3 - "$tmp/j.json" <<'PY' || fail "--json content: $(cat "$tmp/j.json")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["period_us"] == 500 and r["realtime"] is None and r["load"] is False, r
assert 590 <= r["cycles"] <= 601, r["cycles"]
lat = r["wake_latency"]
assert lat["samples"] == r["cycles"] and sum(b["count"] for b in lat["bins"]) == lat["samples"]
assert lat["min_us"] <= lat["mean_us"] <= lat["max_us"] and lat["p99_us"] <= lat["max_us"]
rec = r["recommended_min_period_us"]
assert rec is None or rec >= 2 * lat["max_us"], (rec, lat["max_us"])
PY
echo "ok: --json"

for bad in "--duration 0s" "--duration -1s" "--seconds 0" "--period 10us" "--period 2s" "--period fast" "--realtime=0" "--realtime=100"; do
  # shellcheck disable=SC2086
  "$hb" latency $bad >"$tmp/bad" 2>&1; rc=$?
  [[ $rc -eq 2 ]] || fail "latency $bad exited $rc, expected 2: $(cat "$tmp/bad")"
done
grep -q "realtime" "$tmp/bad" || fail "no option name in: $(cat "$tmp/bad")"
echo "ok: bad options exit 2"

[[ $(id -u) -eq 0 ]] || { echo "not root: real-time path not measured"; exit 77; }
"$hb" latency --duration 300ms --realtime=30 --load --json >"$tmp/rt.json" 2>"$tmp/err"; rc=$?
if [[ $rc -eq 2 ]] && grep -q "was refused" "$tmp/err"; then echo "refused here: $(cat "$tmp/err")"; exit 77; fi
[[ $rc -eq 0 ]] || fail "--realtime exited $rc: $(cat "$tmp/err")"
python3 - "$tmp/rt.json" <<'PY' || fail "--realtime --json content: $(cat "$tmp/rt.json")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["realtime"]["policy"] == "SCHED_FIFO" and r["realtime"]["priority"] == 30, r["realtime"]
assert r["realtime"]["absolute_sleeps"] and r["load"] is True
print(f"ok: SCHED_FIFO under load: mean {r['wake_latency']['mean_us']:.1f} us, max {r['wake_latency']['max_us']:.1f} us")
PY
