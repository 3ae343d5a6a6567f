#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate wf725` over its pty (python3-serial;
# 3964R and RK512 in s5_plc_link.py, no hilbridge code on this side): write a program into a user
# DB and read it in with data code 44 (a faulty one is refused with its number), read it back
# with data code 45, synchronize, select automatic and start, read the actual value while the
# axis moves, drive into a limit switch and read the error word, acknowledge with 800C.
#   plc_wf725.py HILBRIDGE MD-LIST                 the simulated axis: into the pre-limit MD 13 (96)
#   plc_wf725.py HILBRIDGE --machine MACHINE-FILE  retrofit mode: the axis on the machine file's
#       CiA 402 drive, whose positive limit switch (0x60FD) is wired to the WF's limit input (16)
# Run by ctest; exit 77 = skipped (python3-serial missing).
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plc_check import check, finish, stop  # verdicts, the emulator's end
try:
    from s5_plc_link import Link, s32
    from wf_plc import AUTOMATIC, DW_ENABLE, DW_PROGRAM, MDI, PROGRAM_IO, SET_ACTUAL, TRAVERSING, WfAxis, db_text, text_db
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
MACHINE = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--machine" else None
MD = None if MACHINE else sys.argv[2]
DB = 10  # the DB axis

PROGRAM = """%7 A
N1 G90 X 20 000 F 300 000
N2 G90 X 50 000 F 600 000
N3 G90 X 5 000 F 300 000
"""
BAD = "%8\nN1 G90 G91 X 100 F 1000\n"


def main():
    args = [HILBRIDGE, "emulate", "wf725", "--pty", "--format", "8N1", "--state", "none"]
    args += ["--machine", MACHINE] if MACHINE else ["--md", MD]
    p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        path = p.stdout.readline().strip()
        if not path.startswith("/dev/pts/"):
            check("emulator printed its pty", False, path + p.stderr.read())
            return
        wf = WfAxis(Link(path), DB)
        # Program input by data code 44 from a user DB (mode program input/output).
        check("program text into user DB20", wf.link.send(20, 0, text_db(PROGRAM)) == 0)
        check("faulty program into user DB21", wf.link.send(21, 0, text_db(BAD)) == 0)
        done, refused, _, io = wf.data_code(0x44, 20)
        check("data code 44 outside mode program I/O: 201", refused and io == 0x0201, (done, refused, hex(io)))
        wf.mode(PROGRAM_IO, 0)
        done, refused, _, io = wf.data_code(0x44, 20)
        check("program 7 read in from DB20", done and not refused and io == 0, (done, refused, hex(io)))
        done, refused, _, io = wf.data_code(0x44, 21)
        check("faulty program: 232 (second G of group 1), refused", refused and io == 0x0232, (refused, hex(io)))
        done, refused, _, io = wf.data_code(0x45, 8, 22)
        check("faulty program 8 not stored: output gives 127", refused and io == 0x0127, (refused, hex(io)))
        done, refused, _, io = wf.data_code(0x45, 7, 22)
        err, words = wf.link.fetch(22, 0, 1)
        err, words = wf.link.fetch(22, 0, 1 + (words[0] + 1) // 2)
        text = db_text(words) if err == 0 else ""
        check("program 7 read out into DB22 (data code 45)",
              done and not refused and "%7" in text and "N2" in text and "X50000" in text.replace(" ", ""), text)
        err, _ = wf.link.fetch(33, 0, 1)
        check("FETCH of a DB that does not exist: 08", err == 0x08, hex(err))
        err, md = wf.link.fetch(1, 0, 100)
        check("MD image DB1: MD 13 = 96417", err == 0 and s32(md[24], md[25]) == 96417, md[24:26])
        check("MD image write outside mode MD I/O refused (06)", wf.link.send(1, 0, md[:2]) == 0x06)
        # Traversing: synchronize (setting actual value, MD 28 = 0), then automatic.
        wf.mode(TRAVERSING, SET_ACTUAL)
        wf.write(DW_ENABLE, 1)  # D 2.0 drive enable
        time.sleep(0.2)
        wf.pulse(0, until=lambda s: s["syn"])
        s, _ = wf.wait(lambda s: s["syn"], 5)
        check("synchronized (D 3.6), actual 0", s["syn"] and s["actual"] == 0 and s["error"] == 0, s)
        wf.mode(TRAVERSING, AUTOMATIC)
        wf.write(DW_PROGRAM, 7)
        wf.pulse(0, until=lambda s: s["program_active"] or s["actual"] != 0)
        s, samples = wf.wait(lambda s: not s["program_active"] and s["peh"] and s["actual"] == 5000)
        moving = sorted({x["actual"] for x in samples if 0 < x["actual"] < 50000 and x["actual"] not in (5000, 20000)})
        check("actual values read while the axis moves", len(moving) >= 5, moving[:10])
        peak = max(x["actual"] for x in samples)
        check("N2 turned at 50 mm (the peak the PLC saw)", 45000 <= peak <= 50000, peak)
        check("program end: actual 5 mm, PEH, no error", s["actual"] == 5000 and s["peh"] and s["error"] == 0, s)
        # Into a limit switch: MDI to 200 mm.
        wf.mode(TRAVERSING, MDI)
        wf.data_code(0x19, 200000)
        wf.data_code(0x1A, 600000)
        wf.pulse(0, until=lambda s: not s["peh"] or s["error"] != 0)
        s, _ = wf.wait(lambda s: s["error"] != 0 and not s["program_active"], 40)
        time.sleep(0.3)
        s = wf.status()
        if MACHINE:
            check("range limit switch +: error word 16, D 3.4 + D 3.5", s["error"] == 0x16 and s["limit"] and s["strobe"], s)
            check("stopped behind the switch at 60 mm", 60000 <= s["actual"] < 96417, s)
            p.stdin.write("machine\n")
            p.stdin.flush()
            line = p.stdout.readline().strip()
            words = line.split()
            pos = float(words[4]) if len(words) > 5 and words[3] == "position" else None
            check("the CiA 402 axis stands where the module says",
                  pos is not None and abs(pos * 1000 - s["actual"]) <= 5, f"{line!r}, module actual {s['actual']}")
        else:
            check("pre-limit switch +: error word 96, D 3.3 + D 3.5", s["error"] == 0x96 and s["pre_limit"] and s["strobe"], s)
            check("stopped exactly on MD 13 (96.417 mm)", s["actual"] == 96417, s)
        _, refused, _, _ = wf.data_code(0x800C)
        s = wf.status()
        check("800C acknowledges: error word 0", s["error"] == 0 and not s["strobe"], s)
        wf.write(DW_ENABLE, 1)  # drive enable again after a drive-off error
        time.sleep(0.2)
        wf.data_code(0x19, 10000)
        wf.pulse(0, until=lambda s: not s["peh"] or s["actual"] == 10000)
        s, _ = wf.wait(lambda s: s["peh"] and s["actual"] == 10000, 30)
        check("back to 10 mm after the acknowledgement", s["error"] == 0, s)
    finally:
        stop(p)
    finish()


main()
