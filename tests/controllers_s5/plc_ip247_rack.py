#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate ip247` with a rack of two modules
# (--tile 0 --tile 4, docs/ip247.md "Several modules on the line"), one pty each (python3-serial;
# 3964R and RK512 from s5_plc_link.py, no hilbridge code on this side): each module gets its own MD
# DB 1 and its own program 10 (the same DB numbers, different texts); module 1's program runs while
# module 2 stands, then module 2's; the PLC's DBs (DX 5..255) are the rack's (a DB sent on line 1 is
# the target of a data job of module 2); a limit switch of module 2 (26) leaves module 1 alone; after a
# restart with the same state file each module has its own program 10 back. Run by ctest; exit 77 =
# skipped (python3-serial missing). Optional `--machine FILE`: both modules' axis 1 drive a machine
# axis of FILE (one machine per module), and the console's `machine` shows where each module put it.
import os
import subprocess
import sys
import tempfile
import time

from plc_check import check, finish, stop  # verdicts, the emulator's end

try:
    from s5_plc_link import Link, dd  # 3964R + RK512, the PLC side (python3-serial)
    from ip247_plc import md_db, vp_db, status, wait_finished, data_job
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
MACHINE = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--machine" else None

PROG1 = "%10 M1\nN10 X50 F3000 M10\nN20 G04 F1\nN30 X0 F3000 M20\nN40 M02\n"
PROG2 = "%10 M2\nN10 X20 F1500 M30\nN20 X-5 F1500\nN30 M02\n"


def start(state):
    args = [HILBRIDGE, "emulate", "ip247", "--pty", "--format", "8N1", "--state", state, "--tile", "0", "--tile", "4",
            "--switch", "2.1:limit-end:6000"]
    if MACHINE:
        args += ["--machine", MACHINE, "--machine", MACHINE]
    p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    paths = [p.stdout.readline().strip(), p.stdout.readline().strip()]
    check("emulator printed one pty per module", all(x.startswith("/dev/pts/") for x in paths) and
          paths[0] != paths[1], paths)
    return p, [Link(x) for x in paths]


def console(p, cmd, lines):
    p.stdin.write(cmd + "\n")
    p.stdin.flush()
    out = []
    while len(out) < lines:  # a reply ending in a newline prints an empty line after it
        line = p.stdout.readline().rstrip("\n")
        if line:
            out.append(line)
    return out


def main():
    state_dir = tempfile.mkdtemp(prefix="ip247-rack-")
    state = os.path.join(state_dir, "rack.json")
    p, (m1, m2) = start(state)
    try:
        for i, link in enumerate((m1, m2)):
            check(f"module {i + 1}: MD DB1 accepted", link.send(1, 0, md_db(1)) == 0)
        check("module 1: VP DB10 accepted", m1.send(10, 0, vp_db(10, PROG1)) == 0)
        check("module 2: its own VP DB10 accepted", m2.send(10, 0, vp_db(10, PROG2)) == 0)
        err, w1 = m1.fetch(10, 0, 5)
        err2, w2 = m2.fetch(10, 0, 5)
        check("each line shows its module's DB10", err == 0 and err2 == 0 and w1[0] != w2[0], (w1, w2))
        for i, link in enumerate((m1, m2)):
            check(f"module {i + 1}: BA5 set reference", link.send(1, 0, [0x0501, 0, 0, 0, 0x0001], typ="X") == 0)
        check("module 1: BA8 program 10", m1.send(1, 0, [0x080A, 0, 0, 0, 0x0001], typ="X") == 0)
        other = []
        deadline = time.time() + 30
        s1 = status(m1)
        samples1 = []
        while time.time() < deadline and not s1["attr"] & 0x80:
            samples1.append(s1["actual"])
            other.append(status(m2)["actual"])
            time.sleep(0.05)
            s1 = status(m1)
        check("module 1 ran its program (actual values while it moved)",
              len([a for a in samples1 if 0 < a < 50000]) >= 3 and s1["actual"] == 0 and s1["m"] == 2, samples1[:20])
        check("module 2 stood still meanwhile", other and all(a == 0 for a in other), other[:20])
        check("module 2: BA8 its own program 10", m2.send(1, 0, [0x080A, 0, 0, 0, 0x0001], typ="X") == 0)
        s2, samples2 = wait_finished(m2)
        check("module 2 ran its own program: -5 mm, M30 seen, M02", s2["actual"] == -5000 and s2["m"] == 2 and
              any(x["m"] == 30 for x in samples2) and s2["error"] == 0, s2)
        check("module 1 still at 0", status(m1)["actual"] == 0)
        # The PLC's DBs are the rack's: DB 60 sent on line 1, filled by a data job of module 2 (SSNR 7).
        check("PLC DB60 created on line 1 (DX 60)", m1.send(60, 0, [0] * 9, typ="X") == 0)
        w = data_job(m2, 70, z_db=60, ssnr=7)
        err, sysid = m1.fetch(60, 0, 9, typ="X")
        check("BA70 of module 2 into the PLC's DB60, read on line 1", w[0] == 0 and w[6] == 0 and err == 0 and
              sysid[:3] == [0x4950, 0x3234, 0x3720], (w[:10], [hex(x) for x in sysid]))
        w = data_job(m1, 70, z_db=60, ssnr=7)
        check("SSNR 7 is not module 1's (MB250 1)", w[7] >> 8 == 1, w[:10])
        # Module 2 into its end limit switch (60 mm): 26 there, module 1 untouched.
        check("module 2: BA7 forward 100 mm", m2.send(1, 0, [0x0700, 0] + dd(100000) + [0x0004], typ="X") == 0)
        s2, _ = wait_finished(m2)
        check("module 2: limit switch end, error word 26", s2["error"] == 26 and s2["actual"] >= 60000, s2)
        s1 = status(m1)
        check("module 1: no error", s1["error"] == 0 and s1["actual"] == 0, s1)
        out = console(p, "axes", 6)
        check("console axes: both modules", out[0].startswith("module 1 (tile 0) axis 1:") and
              out[3].startswith("module 2 (tile 4) axis 1:") and "error 26" in out[3], out)
        images = [m1.fetch(10, 0, m1.fetch(10, 0, 1)[1][0]), m2.fetch(10, 0, m2.fetch(10, 0, 1)[1][0])]
        if MACHINE:
            time.sleep(0.5)  # the plants settle on the last pulse
            out = console(p, "machine", 2)
            pos = [int(x.split()[8]) if len(x.split()) > 9 and x.split()[7] == "position" else None for x in out]
            check("machine axes where each module's pulses put them (10 um/pulse)",
                  pos[0] is not None and pos[1] is not None and abs(pos[0] * 10 - 0) <= 10 and
                  abs(pos[1] * 10 - s2["actual"]) <= 10, (out, s2["actual"]))
    finally:
        stop(p)
    check("one state file per module, by tile", os.path.exists(os.path.join(state_dir, "rack-tile0.json")) and
          os.path.exists(os.path.join(state_dir, "rack-tile4.json")), os.listdir(state_dir))
    # Restart: each module has its own images back.
    p, (m1, m2) = start(state)
    try:
        after = [m1.fetch(10, 0, images[0][1][0]), m2.fetch(10, 0, images[1][1][0])]
        check("after the restart module 1 has its program 10", after[0] == images[0] and images[0][0] == 0,
              (after[0][0], after[0][1][:8]))
        check("after the restart module 2 has its program 10", after[1] == images[1] and images[1][0] == 0 and
              images[0][1] != images[1][1], (after[1][0], after[1][1][:8]))
        check("module 2: BA5, BA8 runs it again", m2.send(1, 0, [0x0501, 0, 0, 0, 0x0001], typ="X") == 0 and
              m2.send(1, 0, [0x080A, 0, 0, 0, 0x0001], typ="X") == 0)
        s2, _ = wait_finished(m2)
        check("module 2 ends at -5 mm again", s2["actual"] == -5000 and s2["error"] == 0, s2)
    finally:
        stop(p)
    finish()


main()
