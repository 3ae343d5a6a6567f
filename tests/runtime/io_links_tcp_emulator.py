# SPDX-License-Identifier: MIT
"""io_links: modbus with `bus: tcp://` end to end, two processes: `hilbridge emulate modbus-io`
(discrete input 3 set) and `hilbridge run` (real time) whose scenario reads it as the WF axis'
reference cam and writes in_position_A to coil 17 (the emulator prints the change). Then the
emulator is stopped in the middle of a second run: that run must fail with the link's fault.
Every wait has a deadline. Usage: /usr/bin/python3 io_links_tcp_emulator.py HILBRIDGE"""
import os
import queue
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))

SCENARIO = """period: 1ms
controller: {{device: wf725-726, parameters: {params}}}
machine:
  axes:
    - name: A
      drive: {{transport: sim, kv: 100, feedforward: 1.0}}
io_links:
  - modbus: {{bus: "tcp://127.0.0.1:{port}", poll: 5ms, status: "E 0.7"}}
    inputs:
      reference_cam_A: {{discrete_input: 3}}
    outputs:
      in_position_A: {{coil: 17}}
program:
  - enable: A
  - move_relative: {{axis: A, distance: 2}}
  - wait: {wait}
expect:
  - {{io: reference_cam_A, state: true, at: 100ms}}
  - {{io: "E 0.7", state: true, at: 100ms}}
"""


def fail(msg, *procs):
    print(f"FAIL: {msg}")
    for p in procs:
        if p.poll() is None:
            p.kill()
            p.wait(timeout=5)
    sys.exit(1)


class Lines:
    """Collects a process' stdout on a thread; wait_for() a matching line with a deadline."""

    def __init__(self, proc):
        self.q = queue.Queue()
        self.all = []

        def pump():
            for line in proc.stdout:
                self.all.append(line)
                self.q.put(line)
            self.q.put(None)

        threading.Thread(target=pump, daemon=True).start()

    def wait_for(self, pattern, timeout_s):
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                line = self.q.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                return None
            if line is None:
                return None
            m = re.search(pattern, line)
            if m:
                return m


def main():
    hilbridge = sys.argv[1]
    emu = subprocess.Popen([hilbridge, "emulate", "modbus-io", "--listen", "127.0.0.1:0", "--set-input", "3"],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    emu_lines = Lines(emu)
    m = emu_lines.wait_for(r"listening on 127\.0\.0\.1:(\d+) unit 1", 10)
    if not m:
        fail(f"the emulator did not listen: {''.join(emu_lines.all)}", emu)
    port = int(m.group(1))
    tmp = tempfile.mkdtemp(prefix="hil-io-links-tcp-")
    params = os.path.join(ROOT, "examples", "controllers", "wf725-axis-a.txt")

    # 1. A passing run: input from the terminal, output to its coil.
    path = os.path.join(tmp, "ok.yaml")
    with open(path, "w") as f:
        f.write(SCENARIO.format(params=params, port=port, wait="300ms"))
    try:
        run = subprocess.run([hilbridge, "run", "--quiet", path], capture_output=True, text=True, timeout=20)
    except subprocess.TimeoutExpired:
        fail("the run did not end within 20 s", emu)
    if run.returncode != 0:
        fail(f"run exited {run.returncode}:\n{run.stdout}\n{run.stderr}", emu)
    if not emu_lines.wait_for(r"modbus-io: coil 17 -> 1", 5):
        fail(f"coil 17 never switched on: {''.join(emu_lines.all)}", emu)

    # 2. The terminal goes away mid-run: the run fails with the link's fault.
    path = os.path.join(tmp, "outage.yaml")
    with open(path, "w") as f:
        f.write(SCENARIO.format(params=params, port=port, wait="1500ms"))
    run = subprocess.Popen([hilbridge, "run", "--quiet", path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True)
    # The link rewrites every coil after a (re)connect: wait for this run's in_position write
    # (coil 17 goes 1 -> 0 at the move, then 1 again), then stop the terminal.
    if not emu_lines.wait_for(r"modbus-io: coil 17 -> 0", 5) or not emu_lines.wait_for(r"modbus-io: coil 17 -> 1", 5):
        fail(f"the second run never moved: {''.join(emu_lines.all)}", emu, run)
    emu.send_signal(signal.SIGTERM)
    try:
        emu.wait(timeout=10)
        out, _ = run.communicate(timeout=20)
    except subprocess.TimeoutExpired:
        fail("the emulator or the run did not end in time", emu, run)
    if run.returncode != 1:
        fail(f"the run with the outage exited {run.returncode}, want 1:\n{out}")
    if not re.search(r"io_links\[0\]: I/O link fault at t=[0-9.]+ s: modbus:", out):
        fail(f"no I/O link fault in the summary:\n{out}")
    print("PASS: tcp:// link read discrete input 3 and wrote coil 17; the outage failed the run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
