# SPDX-License-Identifier: MIT
# The PLC side of a WF 725/726 DB axis for the Python PLC tests (docs/wf725.md, "The DB axis"):
# its words, the start bit held until the module reacts, data codes with their parameters, the
# status words, and the user-DB text format of data codes 44/45. No hilbridge code: RK512 through
# s5_plc_link.py only.
import time

from s5_plc_link import dd, s32

# DB axis words
DW_MODE, DW_CONTROL, DW_ENABLE, DW_STATUS, DW_ERROR, DW_PROGRAM = 0, 1, 2, 3, 4, 5
DW_CODE, DW_EXEC, DD_P1, DD_P2, DW_DSTAT, DD_RESULT, DD_ACTUAL, DW_FLAGS, DW_IOERR = 11, 12, 13, 15, 17, 18, 20, 24, 40
TRAVERSING, PROGRAM_IO = 0x01, 0x02  # DL 0 bits
SET_ACTUAL, MDI, AUTOMATIC = 3, 4, 6  # DR 0 submodes


def text_db(text):
    """A program text as a user DB: DW 0 = characters, then two characters per word."""
    raw = text.encode("ascii")
    n = len(raw)
    if n % 2:
        raw += b"\0"
    return [n] + [(raw[i] << 8) | raw[i + 1] for i in range(0, len(raw), 2)]


def db_text(words):
    raw = b"".join(bytes([w >> 8, w & 0xFF]) for w in words[1:])
    return raw[:words[0]].decode("ascii")


class WfAxis:
    """One axis of the module through its DB axis (DB 10, 11, 12 for A, B, C)."""

    def __init__(self, link, db=10):
        self.link, self.db = link, db

    def words(self, dw, n):
        err, w = self.link.fetch(self.db, dw, n)
        assert err == 0, f"FETCH DB{self.db} DW{dw}: {err:#x}"
        return w

    def word(self, dw):
        return self.words(dw, 1)[0]

    def write(self, dw, *words):
        err = self.link.send(self.db, dw, list(words))
        assert err == 0, f"SEND DB{self.db} DW{dw}: {err:#x}"

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

    def start(self):
        """The start bit D 1.0, held until the module reacts: a program runs, an error, or any
        status word changes (the axis moves or is synchronised)."""
        before = self.status()
        self.pulse(0, until=lambda s: s["program_active"] or s["error"] != 0 or s != before)

    def data_code(self, code, p1=0, p2=0):
        """Data code with its parameters (rising edge of D 12.0): (done, refused, DD 18, DW 40)."""
        self.write(DW_CODE, code)
        self.write(DD_P1, *dd(p1), *dd(p2))
        self.write(DW_EXEC, 1)
        deadline = time.time() + 2
        while True:
            w = self.words(DW_DSTAT, 3)
            if w[0] & 3 or time.time() > deadline:
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
        """Polls the status until cond(status); returns (status, every sample)."""
        deadline = time.time() + timeout
        samples = []
        while time.time() < deadline:
            s = self.status()
            samples.append(s)
            if cond(s):
                return s, samples
            time.sleep(0.05)
        raise TimeoutError(f"condition not reached: {samples[-1] if samples else None}")

    def synchronize(self):
        """Set actual value (MD 28 = 0) with the drive enabled."""
        self.mode(TRAVERSING, SET_ACTUAL)
        self.write(DW_ENABLE, 1)  # D 2.0 drive enable
        time.sleep(0.1)
        self.start()


def wait_axes(axes, cond, timeout=30):
    """Polls the axes' status until cond(statuses); returns (statuses, every sample)."""
    deadline = time.time() + timeout
    samples = []
    while time.time() < deadline:
        s = [a.status() for a in axes]
        samples.append(s)
        if cond(s):
            return s, samples
        time.sleep(0.03)
    raise TimeoutError(f"condition not reached: {samples[-1] if samples else None}")
