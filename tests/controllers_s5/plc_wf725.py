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
try:
    from s5_plc_link import Link, dd, s32
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
MACHINE = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--machine" else None
MD = None if MACHINE else sys.argv[2]
DB = 10  # the DB axis
failures = []

# DB axis words (docs/wf725.md, "The DB axis")
DW_MODE, DW_CONTROL, DW_ENABLE, DW_STATUS, DW_ERROR, DW_PROGRAM = 0, 1, 2, 3, 4, 5
DW_CODE, DW_EXEC, DD_P1, DD_P2, DW_DSTAT, DD_RESULT, DD_ACTUAL, DW_FLAGS, DW_IOERR = 11, 12, 13, 15, 17, 18, 20, 24, 40
TRAVERSING, PROGRAM_IO = 0x01, 0x02  # DL 0 bits
SET_ACTUAL, MDI, AUTOMATIC = 3, 4, 6  # DR 0 submodes


def check(name, ok, detail=""):
    if ok:
        print(f"ok   {name}")
    else:
        failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


def text_db(text):
    raw = text.encode("ascii")
    n = len(raw)
    if n % 2:
        raw += b"\0"
    return [n] + [(raw[i] << 8) | raw[i + 1] for i in range(0, len(raw), 2)]


def db_text(words):
    n = words[0]
    raw = b"".join(bytes([w >> 8, w & 0xFF]) for w in words[1:])
    return raw[:n].decode("ascii")


class Wf:
    def __init__(self, link):
        self.link = link

    def words(self, dw, n):
        err, w = self.link.fetch(DB, dw, n)
        assert err == 0, f"FETCH DB{DB} DW{dw}: {err:#x}"
        return w

    def word(self, dw):
        return self.words(dw, 1)[0]

    def write(self, dw, *words):
        err = self.link.send(DB, dw, list(words))
        assert err == 0, f"SEND DB{DB} DW{dw}: {err:#x}"

    def mode(self, bits, submode):
        self.write(DW_MODE, (bits << 8) | submode)
        time.sleep(0.05)

    def pulse(self, bit, until=None):
        """Set control bit `bit`, then clear it: after 50 ms, or once `until(status)` holds (at most
        5 s), as an S5 program keeps a start bit until the module reacts. A bare 50 ms pulse can
        fall between two module cycles of an emulator that a loaded machine holds back."""
        w = self.word(DW_CONTROL)
        self.write(DW_CONTROL, w | (1 << bit))
        time.sleep(0.05)
        if until is not None:
            deadline = time.time() + 5
            while not until(self.status()) and time.time() < deadline:
                time.sleep(0.02)
        self.write(DW_CONTROL, w & ~(1 << bit))
        time.sleep(0.05)

    def data_code(self, code, p1=0, p2=0):
        """Data code with its parameters (rising edge of D 12.0): (done, refused, DD 18, DW 40)."""
        self.write(DW_CODE, code)
        self.write(DD_P1, *dd(p1), *dd(p2))
        self.write(DW_EXEC, 1)
        deadline = time.time() + 2
        while True:
            w = self.words(DW_DSTAT, 3)
            if w[0] & 1 or time.time() > deadline:
                break
            time.sleep(0.02)
        io = self.word(DW_IOERR)
        self.write(DW_EXEC, 0)
        time.sleep(0.03)
        return (w[0] & 1) != 0, (w[0] & 2) != 0, s32(w[1], w[2]), io

    def status(self):
        w = self.words(0, 25)
        return {"peh": bool(w[DW_STATUS] & 1), "pre_limit": bool(w[DW_STATUS] & 8),
                "limit": bool(w[DW_STATUS] & 0x10), "strobe": bool(w[DW_STATUS] & 0x20),
                "syn": bool(w[DW_STATUS] & 0x40), "error": w[DW_ERROR] & 0xFF,
                "actual": s32(w[DD_ACTUAL], w[DD_ACTUAL + 1]), "program_active": bool(w[DW_FLAGS] & 2)}

    def wait(self, cond, timeout=30):
        deadline = time.time() + timeout
        samples = []
        while time.time() < deadline:
            s = self.status()
            samples.append(s)
            if cond(s):
                return s, samples
            time.sleep(0.05)
        raise TimeoutError(f"condition not reached: {samples[-1] if samples else None}")


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
        wf = Wf(Link(path))
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
        try:
            p.stdin.write("quit\n")
            p.stdin.flush()
            p.wait(timeout=10)
        except Exception:
            p.kill()
    if failures:
        print("\n".join(failures))
        sys.exit(1)


main()
