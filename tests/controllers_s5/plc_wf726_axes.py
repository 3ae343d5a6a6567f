#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate wf725` serving a WF 726 with three axes
# (python3-serial; 3964R and RK512 in s5_plc_link.py, no hilbridge code on this side):
#  * DB 10/11/12 are the DB axes of A/B/C, DX 1..3 their MD images (axis B has its own MD 13);
#  * a program read in by data code 44 on axis B is in the module's one memory: axes A and C run it
#    at the same time (live actual values of both), a program valid for B only gives 90 on C;
#  * the memory is the module's: while A runs program 5, deleting it (43) or reading it in again
#    (44) through axis B is refused with 105 and changes nothing;
#  * a combined program started on A moves B (the slave): 69 in B and 6B in A while B is not in
#    submode "0"; then, with B in "0", its G17 pair moves A and B together to their targets;
#  * restart with the same state file: the program memory is back (data code 45 reads it out).
#   plc_wf726_axes.py HILBRIDGE MD-A MD-B
#   plc_wf726_axes.py HILBRIDGE --machine FILE-A FILE-B   one machine file per axis (retrofit mode):
#       both DB axes and MD images, a program read in through B runs on A, the machine axes follow
# Run by ctest; exit 77 = skipped (python3-serial missing).
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plc_check import check, finish, stop  # verdicts, the emulator's end
try:
    from s5_plc_link import Link, s32
    from wf_plc import AUTOMATIC, DW_PROGRAM, PROGRAM_IO, TRAVERSING, WfAxis, db_text, text_db, wait_axes
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
MACHINES = sys.argv[3:5] if sys.argv[2] == "--machine" else None
MD_A, MD_B = (None, None) if MACHINES else (sys.argv[2], sys.argv[3])


PROGRAMS = """%7
N1 G90 X 20 000 F 300 000
N2 G90 X 40 000 F 600 000
N3 G90 X 5 000 F 300 000
%9 B RAM
N1 G91 X 1 000 F 100 000
%5 A
N1 G90 X 30 000 F 60 000
%30 AB
N1 A G17 G90 X 20 000 F 60 000
N2 B X 15 000
"""


def emulator(state, *extra):
    args = [HILBRIDGE, "emulate", "wf725", "--pty", "--format", "8N1", "--state", state]
    if MACHINES:
        args += ["--machine", MACHINES[0], "--machine", MACHINES[1]]
    else:
        args += ["--module", "WF726A", "--md", MD_A, "--md", MD_B, "--md", MD_A]
    args += list(extra)
    p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    path = p.stdout.readline().strip()
    if not path.startswith("/dev/pts/"):
        p.kill()
        raise RuntimeError("emulator printed no pty: " + path + p.stderr.read())
    return p, Link(path)


def first_run(state):
    p, link = emulator(state)
    try:
        a, b, c = WfAxis(link, 10), WfAxis(link, 11), WfAxis(link, 12)
        for ax in (a, b, c):
            err, w = link.fetch(ax.db, 0, 48)
            check(f"DB{ax.db} is a DB axis (48 words)", err == 0 and len(w) == 48, hex(err))
        md13 = []
        for dx in (1, 2, 3):
            err, md = link.fetch(dx, 24, 2, "X")
            md13.append(s32(md[0], md[1]) if err == 0 else None)
        check("DX 1..3: each axis' MD image (MD 13 of B = 50 mm)", md13 == [96417, 50000, 96417], md13)
        err, _ = link.fetch(4, 0, 2, "X")
        check("DX 4 does not exist (a module has 3 axes): 08", err == 0x08, hex(err))
        # Program input on axis B; the memory is the module's.
        check("programs into user DB20", link.send(20, 0, text_db(PROGRAMS)) == 0)
        b.mode(PROGRAM_IO, 0)
        done, refused, _, io = b.data_code(0x44, 20)
        check("programs 7, 9, 5 read in through axis B (44)", done and not refused and io == 0, (done, refused, hex(io)))
        # Axes A and C run program 7 together.
        for ax in (a, c):
            ax.synchronize()
        s, _ = wait_axes([a, c], lambda s: all(x["syn"] for x in s), 5)
        check("A and C synchronized", all(x["syn"] and x["actual"] == 0 for x in s), s)
        for ax in (a, c):
            ax.mode(TRAVERSING, AUTOMATIC)
            ax.write(DW_PROGRAM, 7)
        a.start()
        c.start()
        s, samples = wait_axes([a, c], lambda s: all(not x["program_active"] and x["peh"] and x["actual"] == 5000
                                                for x in s))
        both = [x for x in samples if all(0 < y["actual"] < 40000 and y["program_active"] for y in x)]
        check("A and C move at the same time (actual values of both read in one poll)", len(both) >= 3, len(both))
        check("program 7 ends at 5 mm on A and on C", all(x["actual"] == 5000 and x["error"] == 0 for x in s), s)
        c.write(DW_PROGRAM, 9)
        c.start()
        s, _ = wait_axes([c], lambda s: s[0]["error"] != 0, 5)
        check("program 9 (valid for B only) on axis C: error 90", s[0]["error"] == 0x90, s)
        # While A runs program 5, axis B cannot delete it or read it in again (105).
        a.write(DW_PROGRAM, 5)
        a.start()
        wait_axes([a], lambda s: s[0]["program_active"], 5)
        done, refused, _, io = b.data_code(0x43, 5)
        check("delete program 5 while A runs it: 105", refused and io == 0x0105, (done, refused, hex(io)))
        done, refused, _, io = b.data_code(0x44, 20)
        check("read in program 5 while A runs it: 105", refused and io == 0x0105, (done, refused, hex(io)))
        s, _ = wait_axes([a], lambda s: not s[0]["program_active"] and s[0]["peh"], 10)
        check("program 5 ran to its end on A (30 mm)", s[0]["actual"] == 30000 and s[0]["error"] == 0, s)
        combined(a, b)
        done, refused, _, io = b.data_code(0x43, 7)
        check("program 7 deleted through axis B (43)", done and not refused and io == 0, (done, refused, hex(io)))
        time.sleep(0.5)  # the line is quiet: the emulator saves its state file
    finally:
        stop(p)


def combined(a, b):
    """Combined program 30 on A (the master): its G17 pair moves A (30 -> 20 mm) and B (0 -> 15 mm)."""
    b.synchronize()
    wait_axes([b], lambda s: s[0]["syn"], 5)
    b.mode(TRAVERSING, AUTOMATIC)
    a.write(DW_PROGRAM, 30)
    a.start()
    s, _ = wait_axes([a, b], lambda s: s[0]["error"] != 0 and s[1]["error"] != 0, 5)
    check("combined program with B not in submode 0: 6B in A, 69 in B, nothing moves",
          s[0]["error"] == 0x6B and s[1]["error"] == 0x69 and not s[0]["program_active"] and s[1]["actual"] == 0, s)
    b.mode(TRAVERSING, 0)
    a.data_code(0x800C)  # acknowledge 6B
    a.start()
    s, samples = wait_axes([a, b], lambda s: not s[0]["program_active"] and s[0]["peh"] and s[1]["peh"]
                      and s[0]["actual"] == 20000 and s[1]["actual"] == 15000, 10)
    both = [x for x in samples if 20000 < x[0]["actual"] < 30000 and 0 < x[1]["actual"] < 15000]
    check("the G17 pair moves A and B at the same time (actual values of both in one poll)", len(both) >= 3,
          len(both))
    check("program 30 ends with A at 20 mm and B at 15 mm, no error",
          s[0]["error"] == 0 and s[1]["error"] == 0, s)
    # Along the line: A's distance travelled over B's stays 10:15 while they move.
    # (two FETCHes, not one instant: a loaded machine puts some ms between them, hence the margin)
    ratios = [(30000 - x[0]["actual"]) / x[1]["actual"] for x in both if x[1]["actual"] > 4000]
    check("linear interpolation: A travels 2/3 of B's distance at every poll",
          ratios and all(abs(r - 2 / 3) < 0.2 for r in ratios), ratios)


def second_run(state):
    with open(state) as f:
        saved = json.load(f)
    text = saved.get("module", "")
    check("state file keeps the program memory (programs 9 and 5, not the deleted 7)",
          "%9 B RAM" in text and "%5 A" in text and "%7" not in text, text)
    left = set(os.listdir(os.path.dirname(state))) - {os.path.basename(state), os.path.basename(state) + ".lock"}
    check("no temporary file left beside the state file (atomic save)", not left, left)
    p, link = emulator(state)
    try:
        a, c = WfAxis(link, 10), WfAxis(link, 12)
        c.mode(PROGRAM_IO, 0)
        done, refused, _, io = c.data_code(0x45, 9, 30)
        err, n = link.fetch(30, 0, 1)
        err, words = link.fetch(30, 0, 1 + (n[0] + 1) // 2) if err == 0 else (err, [0])
        out = db_text(words) if err == 0 else ""
        check("after the restart program 9 is in the memory (45 into DB30)",
              done and not refused and out.startswith("%9 B RAM") and "X1000" in out.replace(" ", ""), (io, out))
        done, refused, _, io = c.data_code(0x45, 7, 31)
        check("the deleted program 7 stays deleted: 127", refused and io == 0x0127, (done, refused, hex(io)))
        a.synchronize()
        wait_axes([a], lambda s: s[0]["syn"], 5)
        a.mode(TRAVERSING, AUTOMATIC)
        a.write(DW_PROGRAM, 5)
        a.start()
        s, _ = wait_axes([a], lambda s: not s[0]["program_active"] and s[0]["peh"] and s[0]["actual"] == 30000, 10)
        check("the restored program 5 runs on A", s[0]["error"] == 0, s)
    finally:
        stop(p)


def machine_run():
    p, link = emulator("none")
    try:
        a, b = WfAxis(link, 10), WfAxis(link, 11)
        md13 = []
        for dx in (1, 2):
            err, md = link.fetch(dx, 24, 2, "X")
            md13.append(s32(md[0], md[1]) if err == 0 else None)
        check("two machine files: DX 1/2 are the MD images of A and B", md13 == [96417, 50000], md13)
        err, _ = link.fetch(3, 0, 2, "X")
        check("DX 3 does not exist (two axes): 08", err == 0x08, hex(err))
        check("programs into user DB20", link.send(20, 0, text_db(PROGRAMS)) == 0)
        b.mode(PROGRAM_IO, 0)
        done, refused, _, io = b.data_code(0x44, 20)
        check("programs read in through axis B (44)", done and not refused and io == 0, (done, refused, hex(io)))
        a.synchronize()
        wait_axes([a], lambda s: s[0]["syn"], 5)
        a.mode(TRAVERSING, AUTOMATIC)
        a.write(DW_PROGRAM, 7)
        a.start()
        s, _ = wait_axes([a], lambda s: not s[0]["program_active"] and s[0]["peh"] and s[0]["actual"] == 5000)
        check("program 7 (read in through B) ends at 5 mm on A", s[0]["error"] == 0, s)
        time.sleep(0.2)
        p.stdin.write("machine\n")
        p.stdin.flush()
        lines = [p.stdout.readline().strip(), p.stdout.readline().strip()]
        pos = {w[2].rstrip(":"): float(w[4]) for w in (l.split() for l in lines) if len(w) > 4 and w[3] == "position"}
        check("the machine axes of both files; A stands at 5 mm, B at 0",
              set(pos) == {"A", "B"} and abs(pos["A"] - 5.0) < 0.005 and abs(pos["B"]) < 0.005, lines)
    finally:
        stop(p)


def main():
    if MACHINES:
        machine_run()
        finish()
        return
    with tempfile.TemporaryDirectory() as d:
        state = os.path.join(d, "wf726.json")
        first_run(state)
        second_run(state)
    finish()


main()
