#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# hilbridge run on real time from the command line (usage: realtime_cli.sh HILBRIDGE SCENARIO):
#  1. as nobody (no CAP_SYS_NICE, RLIMIT_RTPRIO 0): exit 2 and a message saying what to do;
#  2. as nobody with --realtime-fallback: the run completes on normal scheduling and says so;
#  3. as root: --realtime --json parses and reports SCHED_FIFO, the histogram and the counts.
# Exit 77 (skipped) when not root or when SCHED_FIFO is refused even to root (a container).
set -u
hb=$1 scenario=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[[ $(id -u) -eq 0 ]] || { echo "not root: the privileged and the dropped-privilege paths need root"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

nobody() { setpriv --reuid=65534 --regid=65534 --clear-groups --inh-caps=-all "$@"; }
cp "$hb" "$tmp/hilbridge" && chmod 755 "$tmp" "$tmp/hilbridge"
cp "$scenario" "$tmp/rt.yaml" && chmod 644 "$tmp/rt.yaml"

# An AddressSanitizer build (CI's) does not lock memory (ASan's mlockall is a no-op): there the
# first privilege checked is /dev/cpu_dma_latency.
asan=0
if nm -D "$hb" 2>/dev/null | grep -q __asan_init; then asan=1; fi

nobody "$tmp/hilbridge" run -q "$tmp/rt.yaml" >"$tmp/out1" 2>"$tmp/err1"; rc=$?
[[ $rc -eq 2 ]] || fail "unprivileged real-time run exited $rc, expected 2: $(cat "$tmp/err1")"
# The first privilege refused is named: mlockall when the process is larger than the unprivileged
# RLIMIT_MEMLOCK, else the DMA latency request (root-only by default), else SCHED_FIFO; each with
# what to do about it.
if grep -qE -- "SCHED_FIFO priority 20 was refused|locking the process' memory was refused" "$tmp/err1"; then
  wants=("setcap cap_sys_nice,cap_ipc_lock=ep" "limits.conf" "--realtime-fallback")
elif grep -qF -- "cannot hold /dev/cpu_dma_latency at 0" "$tmp/err1"; then
  wants=("udev rule" "dma_latency: false" "--realtime-fallback")
else
  fail "message names no refused privilege: $(cat "$tmp/err1")"
fi
for want in "${wants[@]}"; do
  grep -qF -- "$want" "$tmp/err1" || fail "message lacks '$want': $(cat "$tmp/err1")"
done
echo "ok: unprivileged run refused: $(head -c 200 "$tmp/err1")"

nobody "$tmp/hilbridge" run -q --realtime-fallback "$tmp/rt.yaml" >"$tmp/out2" 2>"$tmp/err2"; rc=$?
[[ $rc -eq 0 ]] || fail "fallback run exited $rc: $(cat "$tmp/out2" "$tmp/err2")"
grep -q "real time: normal scheduling (SCHED_OTHER).*fell back: scheduling" "$tmp/out2" ||
  fail "fallback run does not say it fell back: $(cat "$tmp/out2")"
grep -q "wake-up latency histogram:" "$tmp/out2" || fail "no histogram in the summary"
echo "ok: fallback run on normal scheduling"

"$hb" run --json --realtime=30 "$scenario" >"$tmp/out3.json" 2>"$tmp/err3"; rc=$?
if [[ $rc -eq 2 ]] && grep -q "SCHED_FIFO priority 30 was refused" "$tmp/err3"; then
  echo "SCHED_FIFO refused even to root here: $(cat "$tmp/err3")"; exit 77
fi
[[ $rc -eq 0 ]] || fail "root real-time run exited $rc: $(cat "$tmp/err3" "$tmp/out3.json")"
python3 -m json.tool "$tmp/out3.json" >/dev/null || fail "--json output does not parse"
python3 - "$tmp/out3.json" "$asan" <<'PY' || fail "--json content"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["ok"] is True, r["failures"]
rt = r["realtime"]
assert rt["policy"] == "SCHED_FIFO" and rt["priority"] == 30, rt
assert rt["memory_locked"] == (sys.argv[2] == "0") and rt["absolute_sleeps"], rt
s = r["scheduler"]
assert s["virtual_time"] is False and s["cycles"] > 100, s
assert isinstance(s["overruns"], int) and isinstance(s["skipped_cycles"], int)
lat = s["wake_latency"]
assert lat["samples"] == s["cycles"], (lat["samples"], s["cycles"])
assert sum(b["count"] for b in lat["bins"]) == lat["samples"]
print(f"ok: root run SCHED_FIFO {rt['priority']} on CPU {rt['cpu']}: {s['cycles']} cycles, latency mean "
      f"{lat['mean_us']:.1f} us p99 {lat['p99_us']:.1f} us max {lat['max_us']:.1f} us, "
      f"{s['overruns']} overruns, {s['skipped_cycles']} skipped")
PY
