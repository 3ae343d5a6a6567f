#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# kernel-labelled check that the VM gives tests what they are promised: vcan0/vcan1 carry frames
# between two independent processes (can-utils cansend -> candump), and the gpio-sim chip's lines
# read back through the simulator's sysfs. Outside the VM it skips (exit 77) with the reason.
set -euo pipefail
if [[ ! -d /sys/class/net/vcan0 ]]; then
  echo "SKIP: no vcan0 on this kernel; run through tests/vm/run-in-kernel.sh (scripts/test.sh does)"
  exit 77
fi
for n in vcan0 vcan1; do
  [[ $(cat /sys/class/net/$n/operstate) =~ ^(up|unknown)$ ]] || { echo "FAIL: $n is not up"; exit 1; }
done
out=$(mktemp)
candump -n 1 -T 5000 vcan0 > "$out" &
pid=$!
for _ in $(seq 50); do  # wait until candump has bound its socket
  grep -q vcan0 /proc/net/can/rcvlist_all 2>/dev/null && break
  read -r -t 0.05 < /dev/zero || true
done
cansend vcan0 123#DEADBEEF
wait "$pid"
grep -q '123 *\[4\] *DE AD BE EF' "$out" || { echo "FAIL: candump saw: $(cat "$out")"; exit 1; }
echo "vcan0: cansend -> candump OK"
[[ -n "${HIL_GPIOCHIP:-}" && -e "/dev/$HIL_GPIOCHIP" ]] || { echo "FAIL: HIL_GPIOCHIP not set or missing"; exit 1; }
echo pull-up > "$HIL_GPIOSIM_SYSFS/sim_gpio2/pull"
[[ $(gpioget "$HIL_GPIOCHIP" 2) == 1 ]] || { echo "FAIL: gpio-sim pull-up not seen by gpioget"; exit 1; }
echo pull-down > "$HIL_GPIOSIM_SYSFS/sim_gpio2/pull"
[[ $(gpioget "$HIL_GPIOCHIP" 2) == 0 ]] || { echo "FAIL: gpio-sim pull-down not seen by gpioget"; exit 1; }
echo "$HIL_GPIOCHIP: gpio-sim pull -> gpioget OK"
