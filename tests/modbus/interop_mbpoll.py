# SPDX-License-Identifier: MIT
"""mbpoll 1.4 (libmodbus-based CLI master) against our simulated drive server: reads with FC 3
and FC 4, writes with FC 6 and FC 16, and its exit status on an exception.
Usage: /usr/bin/python3 interop_mbpoll.py HILBRIDGE"""
import re
import shutil
import subprocess
import sys

from emulator import Checks, Emulator


def mbpoll(port, *args):
    cmd = ["mbpoll", "-m", "tcp", "-p", str(port), "-a", "1", "-0", "-1", "-o", "2", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=20)
    values = {int(a): int(v, 0) for a, v in re.findall(r"\[(\d+)\]:\s+(-?(?:0x)?[0-9A-Fa-f]+)", p.stdout)}
    return p.returncode, values, p.stdout + p.stderr


def main():
    if not shutil.which("mbpoll"):
        sys.exit("mbpoll not installed (apt install mbpoll)")
    hilbridge = sys.argv[1]
    c = Checks()
    with Emulator(hilbridge, "cia402") as emu:
        rc, v, out = mbpoll(emu.port, "-r", "10", "-c", "6", "-t", "4:hex", "127.0.0.1")
        c.check(rc == 0 and len(v) == 6, f"FC3 read of 6 registers: rc={rc} {out}")
        c.check(v.get(10, 0) & 0x4F == 0x40, f"status switch on disabled: {v}")
        for cw, want in ((6, 0x21), (7, 0x23), (15, 0x27)):
            rc, _, out = mbpoll(emu.port, "-r", "0", "-t", "4", "127.0.0.1", str(cw))
            c.check(rc == 0, f"FC6 write control word {cw}: {out}")
            rc, v, out = mbpoll(emu.port, "-r", "10", "-c", "1", "-t", "4:hex", "127.0.0.1")
            c.check(rc == 0 and v.get(10, 0) & 0x6F == want, f"status after {cw}: {v} {out}")
        rc, _, out = mbpoll(emu.port, "-r", "4", "-t", "4", "127.0.0.1", "0", "1000")  # FC16: 2 registers
        c.check(rc == 0, f"FC16 write of target velocity: {out}")
        rc, _, out = mbpoll(emu.port, "-r", "10", "-t", "4", "127.0.0.1", "1")
        c.check(rc != 0 and "llegal data address" in out, f"write to read-only status word fails with 02: rc={rc} {out}")
        rc, _, out = mbpoll(emu.port, "-r", "0", "-c", "1", "-t", "0", "127.0.0.1")
        c.check(rc != 0 and "llegal function" in out, f"coils answer 01: rc={rc} {out}")
    with Emulator(hilbridge, "vendor_simple") as emu:
        rc, v, out = mbpoll(emu.port, "-r", "0", "-c", "5", "-t", "3", "127.0.0.1")
        c.check(rc == 0 and len(v) == 5 and v[0] & 1 == 1, f"FC4 vendor status: rc={rc} {out}")
    c.exit()


if __name__ == "__main__":
    main()
