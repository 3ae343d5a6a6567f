#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate wf725` serving a WF 726 whose axes A and
# B are a split drive (gantry, MD 27 = 3 and MD 29 = 100 µm in axis A; docs/wf725.md "Split drive";
# python3-serial, 3964R and RK512 in s5_plc_link.py, no hilbridge code on this side):
#  * both axes synchronized, B in submode "0", A in MDI with the monitoring bit D 2.3: one MDI
#    start on A moves both (live actual values of both, data code 30 read while they move);
#  * data code 31 shifts B 2 mm beyond A, A stands; a coupled move keeps the shift;
#  * B in another submode: A's start gives 6B, B shows 69.
#   plc_wf726_gantry.py HILBRIDGE MD-A MD-B
# Run by ctest; exit 77 = skipped (python3-serial missing).
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plc_check import check, finish, stop  # verdicts, the emulator's end
try:
    from s5_plc_link import Link, s32
    from wf_plc import DW_ENABLE, MDI, TRAVERSING, WfAxis, wait_axes
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE, MD_A, MD_B = sys.argv[1], sys.argv[2], sys.argv[3]
MONITORING = 1 << 3  # D 2.3 in axis A's DB axis


def actual(link, db):
    err, w = link.fetch(db, 20, 2)
    assert err == 0, f"FETCH DB{db} DD 20: {err:#x}"
    return s32(w[0], w[1])


def mdi(a, um, feed):
    a.data_code(0x19, um)
    a.data_code(0x1A, feed)
    a.start()


def main():
    args = [HILBRIDGE, "emulate", "wf725", "--pty", "--format", "8N1", "--state", "none", "--module", "WF726A",
            "--md", MD_A, "--md", MD_B]
    p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    path = p.stdout.readline().strip()
    if not path.startswith("/dev/pts/"):
        p.kill()
        raise RuntimeError("emulator printed no pty: " + path + p.stderr.read())
    link = Link(path)
    try:
        a, b = WfAxis(link, 10), WfAxis(link, 11)
        for ax in (a, b):
            ax.synchronize()
        s, _ = wait_axes([a, b], lambda s: all(x["syn"] for x in s), 5)
        check("A and B synchronized at 0", all(x["syn"] and x["actual"] == 0 for x in s), s)
        b.mode(TRAVERSING, 0)  # the slave in submode "0"
        a.mode(TRAVERSING, MDI)
        a.write(DW_ENABLE, 1 | MONITORING)
        time.sleep(0.1)
        mdi(a, 60000, 300000)  # 60 mm at 3000 mm/min
        s, samples = wait_axes([a, b], lambda s: 20000 < s[0]["actual"] < 40000, 10)
        done, refused, diff, io = a.data_code(0x30)
        check("data code 30 while the gantry moves: a few µm", done and not refused and abs(diff) <= 20,
              (done, refused, diff, hex(io)))
        # B's actual value read between two readings of A's lies between them (the module rewrites
        # DD 20 every cycle; the three FETCH jobs take their time on the line).
        between, outside = 0, []
        while True:
            a1, bb, a2 = actual(link, 10), actual(link, 11), actual(link, 10)
            if a2 >= 59990:
                break
            if a1 > 0:
                if min(a1, a2) - 50 <= bb <= max(a1, a2) + 50:
                    between += 1
                else:
                    outside.append((a1, bb, a2))
        check("B moves with A: its actual value between two of A's while they move (within 50 µm)",
              between >= 3 and not outside, (between, outside[:3]))
        s, samples = wait_axes([a, b], lambda s: all(x["peh"] and x["actual"] in range(59998, 60003) for x in s), 10)
        check("both at 60 mm, no error", s[0]["actual"] == 60000 and all(x["error"] == 0 for x in s), s)
        done, refused, diff, io = a.data_code(0x30)
        check("data code 30 at rest: 0", done and abs(diff) <= 1, (done, refused, diff, hex(io)))
        # Data code 31: B 2 mm beyond A at 600 mm/min.
        done, refused, _, io = a.data_code(0x31, 2000, 60000)
        check("data code 31 accepted", done and not refused and io == 0, (done, refused, hex(io)))
        s, _ = wait_axes([a, b], lambda s: s[1]["actual"] in range(61999, 62002) and s[1]["peh"], 10)
        check("B shifted to 62 mm, A stands at 60 mm", s[0]["actual"] == 60000 and s[0]["error"] == 0, s)
        mdi(a, 30000, 300000)
        s, _ = wait_axes([a, b], lambda s: s[0]["actual"] == 30000 and s[0]["peh"] and s[1]["peh"], 10)
        check("a coupled move keeps the shift: A 30 mm, B 32 mm", abs(s[1]["actual"] - 32000) <= 2, s)
        # The slave outside submode "0": A's start is refused with 6B, B shows 69.
        b.mode(TRAVERSING, MDI)
        mdi(a, 10000, 300000)
        s, _ = wait_axes([a, b], lambda s: s[0]["error"] != 0, 5)
        check("B not in submode 0: 6B in A, 69 in B, nothing moved",
              s[0]["error"] == 0x6B and s[1]["error"] == 0x69 and s[0]["actual"] == 30000, s)
    finally:
        stop(p)
    finish()


main()
