# SPDX-License-Identifier: MIT
"""io_links: modbus against an independent peer: `hilbridge run` (real time) serves its simulated
I/O terminal on a free port (the address is printed before the first cycle); pymodbus (Debian's
python3-pymodbus) waits until coil 17, driven by the controller's in_position_A output, reads 1
(so the run is under way), then writes coil 0, which the scenario expects as the first edge of
reference_cam_A. The run must pass and the CSV trace must show the input rise after the start.
Every wait has a deadline: the test cannot hang (the run is killed after 20 s).
Usage: /usr/bin/python3 io_links_pymodbus.py HILBRIDGE SCENARIO"""
import csv
import os
import queue
import re
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "modbus"))
import pymodbus_compat  # noqa: F401,E402  (before pymodbus)

try:
    from pymodbus.client import ModbusTcpClient  # noqa: E402
except ImportError:
    print("SKIP: python3-pymodbus is not installed for /usr/bin/python3 (apt install python3-pymodbus)")
    sys.exit(77)


def fail(msg, proc=None, out=None):
    print(f"FAIL: {msg}")
    if proc is not None and proc.poll() is None:
        proc.kill()
        proc.wait(timeout=5)
    if out:
        print("--- hilbridge output ---\n" + "".join(out))
    sys.exit(1)


def main():
    hilbridge, scenario = sys.argv[1], sys.argv[2]
    tmp = tempfile.mkdtemp(prefix="hil-io-links-")
    trace = os.path.join(tmp, "trace.csv")
    proc = subprocess.Popen([hilbridge, "run", scenario, "--trace", trace], stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    lines = queue.Queue()
    out = []

    def pump():
        for line in proc.stdout:
            out.append(line)
            lines.put(line)
        lines.put(None)

    threading.Thread(target=pump, daemon=True).start()

    port = None
    deadline = time.monotonic() + 10
    while port is None:
        try:
            line = lines.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            fail("no 'listening on' line within 10 s", proc, out)
        if line is None:
            fail("hilbridge ended before its terminal listened", proc, out)
        m = re.search(r"io_links\[0\]: simulated Modbus I/O terminal listening on 127\.0\.0\.1:(\d+)", line)
        if m:
            port = int(m.group(1))

    cl = ModbusTcpClient("127.0.0.1", port=port, timeout=2)
    if not cl.connect():
        fail(f"pymodbus cannot connect to 127.0.0.1:{port}", proc, out)
    # Handshake, so the edge falls inside the run whatever the timing: coil 17 follows
    # in_position_A, which the link writes only from a controller cycle, once the axis is enabled
    # and in position. Only then does the peer set coil 0.
    seen = False
    deadline = time.monotonic() + 5
    while not seen and time.monotonic() < deadline:
        rr = cl.read_coils(17, 1, slave=1)  # FC 1
        if rr.isError():
            fail(f"FC 1 read coil 17: {rr}", proc, out)
        seen = bool(rr.bits[0])
        if not seen:
            time.sleep(0.005)
    if not seen:
        fail("coil 17 (in_position_A) never became 1 within 5 s", proc, out)
    wr = cl.write_coil(0, True, slave=1)  # FC 5
    if wr.isError():
        fail(f"FC 5 write coil 0: {wr}", proc, out)
    rr = cl.read_coils(0, 1, slave=1)  # the terminal keeps it
    if rr.isError() or not rr.bits[0]:
        fail(f"FC 1 read coil 0 after writing it: {rr}", proc, out)
    di = cl.read_discrete_inputs(0, 8, slave=1)  # FC 2 answers too (the terminal's 64 inputs)
    if di.isError():
        fail(f"FC 2: {di}", proc, out)
    cl.close()

    try:
        rc = proc.wait(timeout=20)
    except subprocess.TimeoutExpired:
        fail("the run did not end within 20 s", proc, out)
    time.sleep(0.05)  # let the pump thread take the last lines
    if rc != 0:
        fail(f"hilbridge run exited with {rc}", None, out)

    with open(trace, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "io_reference_cam_A" not in rows[0]:
        fail(f"trace has no io_reference_cam_A column: {list(rows[0].keys()) if rows else 'no rows'}", None, out)
    first = next((float(r["t_s"]) for r in rows if r["io_reference_cam_A"] == "1"), None)
    if first is None or first <= 0.0:
        fail(f"io_reference_cam_A never rose after the start in the trace (first 1 at {first})", None, out)
    print(f"PASS: pymodbus wrote coil 0 (port {port}); reference_cam_A rose at t={first:.3f} s; "
          f"coil 17 followed in_position_A")
    return 0


if __name__ == "__main__":
    sys.exit(main())
