#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Soak test on real time (not in CI): the socketcand hub with 8 simulated CiA 402 nodes behind it,
# the Modbus drive server, and a step/dir axis, for a long time (default 1 h). Every cycle a fault
# (over-current, EMCY 0x2310) is injected into one node over SDO, must show in its statusword
# (Fault), is cleared and reset (controlword bit 7 edge) and must leave Fault; Modbus clients
# connect, read and drop, idle TCP clients connect and vanish, and the step/dir demo runs with
# its edge streams verified. Memory (RSS) and open file descriptors of the hub, the nodes and the
# Modbus server are sampled every minute; the script fails on a missed fault, a failed client or
# a growth of RSS by more than 20 % / of descriptors by more than 8 after the first minute.
#   scripts/soak.sh [--minutes N] [--hilbridge PATH]
set -uo pipefail
cd "$(dirname "$0")/.."
minutes=60
hil=build/hilbridge
while [[ $# -gt 0 ]]; do
  case "$1" in
    --minutes) minutes=$2; shift 2 ;;
    --seconds) minutes="$2/60"; secs=$2; shift 2 ;;
    --hilbridge) hil=$2; shift 2 ;;
    *) echo "soak.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
secs=${secs:-$(( minutes * 60 ))}
work=$(mktemp -d)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; wait 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT

"$hil" can hub --listen 127.0.0.1:0 >"$work/hub.out" 2>"$work/hub.err" &
pids+=($!); hub_pid=$!
for _ in $(seq 50); do grep -q '[0-9]' "$work/hub.out" 2>/dev/null && break; sleep 0.1; done
port=$(grep -o '127.0.0.1:[0-9]*' "$work/hub.out" "$work/hub.err" | head -1 | sed 's/.*://')
[[ -n "$port" ]] || { echo "soak: hub did not start"; cat "$work/hub.err"; exit 1; }
bus="socketcand://127.0.0.1:$port/can0"
nodes=(); for n in 1 2 3 4 5 6 7 8; do nodes+=(--node "$n"); done
"$hil" emulate cia402 --bus "$bus" "${nodes[@]}" >"$work/nodes.out" 2>&1 &
pids+=($!); nodes_pid=$!
"$hil" emulate modbus-drive --listen 127.0.0.1:0 --quiet >"$work/mb.out" 2>"$work/mb.err" &
pids+=($!); mb_pid=$!
for _ in $(seq 50); do grep -q ':[0-9]' "$work/mb.out" 2>/dev/null && break; sleep 0.1; done
mb_port=$(grep -o ':[0-9][0-9]*' "$work/mb.out" | head -1 | tr -d :)
sleep 1

sample() {  # pid -> "rss_kb fds"
  echo "$(awk '/VmRSS/ {print $2}' /proc/"$1"/status 2>/dev/null) $(ls /proc/"$1"/fd 2>/dev/null | wc -l)"
}
declare -A first=()
faults=0 missed=0 client_fail=0 stepdir_fail=0 cycle=0
start=$(date +%s); next_sample=$start
echo "soak: hub :$port, 8 nodes, modbus :$mb_port, $secs s"
while (( $(date +%s) - start < secs )); do
  cycle=$((cycle + 1))
  node=$(( (cycle % 8) + 1 ))
  # Fault injected over SDO (0x2100 = error code), seen in the statusword, cleared and reset.
  "$hil" sdo write --bus "$bus" "$node" 0x2100:0 0x2310 --type u16 >/dev/null 2>&1
  faults=$((faults + 1))
  sw=$("$hil" sdo read --bus "$bus" "$node" 0x6041:0 --type u16 2>/dev/null | grep -o '[0-9]*' | tail -1)
  if [[ -z "$sw" ]] || (( (sw & 0x8) == 0 )); then missed=$((missed + 1)); echo "soak: fault $cycle on node $node not seen (statusword ${sw:-none})"; fi
  "$hil" sdo write --bus "$bus" "$node" 0x2100:0 0 --type u16 >/dev/null 2>&1
  "$hil" sdo write --bus "$bus" "$node" 0x6040:0 0 --type u16 >/dev/null 2>&1
  "$hil" sdo write --bus "$bus" "$node" 0x6040:0 0x80 --type u16 >/dev/null 2>&1
  sw=$("$hil" sdo read --bus "$bus" "$node" 0x6041:0 --type u16 2>/dev/null | grep -o '[0-9]*' | tail -1)
  if [[ -z "$sw" ]] || (( (sw & 0x8) != 0 )); then missed=$((missed + 1)); echo "soak: node $node still in fault after the reset"; fi
  # Modbus clients that connect, read and drop; idle TCP clients that vanish.
  "$hil" modbus read "127.0.0.1:$mb_port" 1 0 4 >/dev/null 2>&1 || { client_fail=$((client_fail + 1)); echo "soak: modbus read failed"; }
  (exec 3<>/dev/tcp/127.0.0.1/"$mb_port"; sleep 0.2) 2>/dev/null &
  (exec 3<>/dev/tcp/127.0.0.1/"$port"; sleep 0.2) 2>/dev/null &
  # The step/dir axis (mock lines, verified edge streams) every 10th cycle.
  if (( cycle % 10 == 0 )); then
    "$hil" run --virtual --quiet --verify-steps examples/stepdir-demo.yaml >/dev/null 2>&1 || { stepdir_fail=$((stepdir_fail + 1)); echo "soak: stepdir run failed"; }
  fi
  now=$(date +%s)
  if (( now >= next_sample )); then
    line="t=$((now - start))s"
    for name in hub nodes mb; do
      pv="${name}_pid"; s=$(sample "${!pv}")
      [[ -z "${first[$name]:-}" && $((now - start)) -ge 60 ]] && first[$name]=$s
      line+=" $name(rss_kb fds)=$s"
    done
    echo "soak: $line"
    next_sample=$((now + 60))
  fi
done
sleep 0.5  # the last idle clients' subshells end
status=0
echo "soak: $cycle cycles, $faults faults injected, $missed missed, $client_fail client failures, $stepdir_fail step/dir failures"
(( missed == 0 && client_fail == 0 && stepdir_fail == 0 )) || status=1
for name in hub nodes mb; do
  pv="${name}_pid"; kill -0 "${!pv}" 2>/dev/null || { echo "soak: $name died"; status=1; continue; }
  [[ -n "${first[$name]:-}" ]] || continue
  read -r rss0 fd0 <<<"${first[$name]}"; read -r rss1 fd1 <<<"$(sample "${!pv}")"
  echo "soak: $name rss ${rss0} -> ${rss1} kB, fds ${fd0} -> ${fd1}"
  (( rss1 * 10 > rss0 * 12 || fd1 > fd0 + 8 )) && { echo "soak: $name grows"; status=1; }
done
exit $status
