#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate ip247` over its pty (python3-serial;
# 3964R and RK512 implemented here from the notes, no hilbridge code on this side): write an MD
# DB and a traversing-program DB, select automatic and start, read the actual value while the
# axis moves, drive into the "end" limit switch and read the error word. Run by ctest; exit 77 =
# skipped (python3-serial missing).
import struct
import subprocess
import sys
import time

try:
    import serial  # python3-serial
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
# Optional: `--machine FILE`: the emulator's axis 1 drives the machine axis of FILE (retrofit mode);
# the script then also checks that the machine axis stands where the module's pulses put it.
MACHINE = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--machine" else None
STX, ETX, DLE, NAK = 0x02, 0x03, 0x10, 0x15
failures = []


def check(name, ok, detail=""):
    if ok:
        print(f"ok   {name}")
    else:
        failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


class Link:
    """3964R (with BCC) plus RK512 SEND/FETCH, the PLC side."""

    def __init__(self, path):
        self.port = serial.Serial(path, 9600, bytesize=8, parity="N", stopbits=1, timeout=2)

    def read1(self):
        c = self.port.read(1)
        if not c:
            raise TimeoutError("no character within 2 s")
        return c[0]

    def send_block(self, payload: bytes):
        body = bytearray()
        for b in payload:
            body.append(b)
            if b == DLE:
                body.append(DLE)
        body += bytes([DLE, ETX])
        bcc = 0
        for b in body:
            bcc ^= b
        for _ in range(6):
            self.port.write(bytes([STX]))
            if self.read1() != DLE:
                time.sleep(0.05)
                continue
            self.port.write(bytes(body) + bytes([bcc]))
            if self.read1() == DLE:
                return
        raise RuntimeError("3964R: block not acknowledged")

    def recv_block(self) -> bytes:
        deadline = time.time() + 5
        while self.read1() != STX:
            if time.time() > deadline:
                raise TimeoutError("no STX")
        self.port.write(bytes([DLE]))
        data, bcc = bytearray(), 0
        while True:
            c = self.read1()
            bcc ^= c
            if c == DLE:
                d = self.read1()
                bcc ^= d
                if d == ETX:
                    break
                data.append(d)  # doubled DLE
            else:
                data.append(c)
        if self.read1() != bcc:
            self.port.write(bytes([NAK]))
            raise RuntimeError("3964R: BCC error")
        self.port.write(bytes([DLE]))
        return bytes(data)

    def reaction(self, expect_bytes=0):
        t = self.recv_block()
        assert t[0] == 0 and t[1] == 0 and t[2] == 0, t.hex()
        err, data = t[3], bytearray(t[4:])
        while err == 0 and len(data) < expect_bytes:
            c = self.recv_block()
            assert c[0] == 0xFF
            data += c[4:]
        return err, bytes(data)

    def send(self, typ, db, dw, words):
        data = b"".join(struct.pack(">H", w & 0xFFFF) for w in words)
        cmd = ord("A") if typ == "D" else ord("O")
        first = bytes([0, 0, cmd, ord(typ), db, dw, len(words) >> 8, len(words) & 0xFF, 0xFF, 0xFF])
        self.send_block(first + data[:128])
        pos = 128
        while pos < len(data):
            self.send_block(bytes([0xFF, 0, cmd, ord(typ)]) + data[pos:pos + 128])
            pos += 128
        return self.reaction()[0]

    def fetch(self, typ, db, dw, n):
        self.send_block(bytes([0, 0, ord("E"), ord(typ), db, dw, n >> 8, n & 0xFF, 0xFF, 0xFF]))
        err, data = self.reaction(2 * n)
        return err, [struct.unpack(">H", data[i:i + 2])[0] for i in range(0, len(data), 2)]


def dd(v):
    v &= 0xFFFFFFFF
    return [v >> 16, v & 0xFFFF]


def s32(hi, lo):
    v = (hi << 16) | lo
    return v - (1 << 32) if v & 0x80000000 else v


def md_db(db):
    """MD DB (manual §6.3.8.1): 10 µm/pulse, fmax 5 kHz, NO limit switches, 70 words."""
    w = [70, 0x0044, 0x4200 | db, (0 << 8) | 1, (1 << 8) | 0]
    w += dd(5000) + dd(200) + dd(50000)          # fmax, fss, a (mHz/ms)
    w += [30, 0x40, 4, 200] + dd(2000)           # pulse, polarity, patterns, pulses/rev, gear
    w += dd(3000) * 4                            # jog 1, jog 2, incremental, reference speed
    w += [1, 0x20] + dd(0) + dd(-400000) + dd(500000)  # sync no, ref backward, ref coord, SW limits
    w += [0] + dd(0) + dd(0) + dd(0) * 4 + [0, 0]      # NO switches, tool, backlash, zero offsets, linear, binary
    w += [0] * (70 - len(w))
    return w


def vp_db(db, text):
    raw = text.encode("ascii")
    if len(raw) % 2:
        raw += b"\0"
    words = [(raw[i] << 8) | raw[i + 1] for i in range(0, len(raw), 2)]
    return [5 + len(words), 0x0044, 0x4200 | db, 0, 0] + words


def status(link):
    err, w = link.fetch("X", 1, 0, 14)
    assert err == 0, err
    return {"actual": s32(w[5], w[6]), "remaining": s32(w[9], w[10]), "ba": w[11] >> 8, "m": w[11] & 0xFF,
            "attr": w[12] >> 8, "error": w[12] & 0xFF}


def wait_finished(link, timeout=30):
    deadline = time.time() + timeout
    samples = []
    while time.time() < deadline:
        s = status(link)
        samples.append(s)
        if s["attr"] & 0x80:
            return s, samples
        time.sleep(0.05)
    raise TimeoutError("axis did not finish")


def main():
    args = [HILBRIDGE, "emulate", "ip247", "--pty", "--format", "8N1", "--state", "none", "--switch",
            "1:limit-end:6000"]
    if MACHINE:
        args += ["--machine", MACHINE]
    p = subprocess.Popen(args, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        path = p.stdout.readline().strip()
        check("emulator printed its pty", path.startswith("/dev/pts/"), path)
        link = Link(path)
        check("MD DB1 accepted", link.send("D", 1, 0, md_db(1)) == 0)
        err, back = link.fetch("D", 1, 0, 70)
        check("MD DB1 read back", err == 0 and back == md_db(1), f"{err} {back[:6]}")
        prog = "%10 PLC\nN10 X50 F3000 M10\nN20 G04 F2\nN30 X0 F3000 M20\nN40 M02\n"
        check("VP DB10 accepted", link.send("D", 10, 0, vp_db(10, prog)) == 0)
        check("VP DB10 again: no overwrite (07)", link.send("D", 10, 0, vp_db(10, prog)) == 0x07)
        bad = "%11\nN10 X1 F10 M100\nN20 M02\n"
        check("faulty VP DB11 rejected (10h)", link.send("D", 11, 0, vp_db(11, bad)) == 0x10)
        check("faulty VP DB11 not stored", link.fetch("D", 11, 0, 5)[0] == 0x08)
        s = status(link)
        check("reference missing before BA5", s["attr"] & 0x20 != 0, s)
        check("BA5 set reference", link.send("X", 1, 0, [0x0501, 0, 0, 0, 0x0001]) == 0)
        s = status(link)
        check("reference set", s["attr"] & 0x20 == 0 and s["error"] == 0, s)
        check("BA8 program 10 start", link.send("X", 1, 0, [0x080A, 0, 0, 0, 0x0001]) == 0)
        s, samples = wait_finished(link)
        moving = [x["actual"] for x in samples if 0 < x["actual"] < 50000]
        check("actual values read while moving", len(moving) >= 3, [x["actual"] for x in samples][:20])
        check("M10 seen while running", any(x["m"] == 10 for x in samples))
        check("program end: actual 0, M02, no error", s["actual"] == 0 and s["m"] == 2 and s["error"] == 0, s)
        check("BA7 forward 100 mm", link.send("X", 1, 0, [0x0700, 0] + dd(100000) + [0x0004]) == 0)
        s, _ = wait_finished(link)
        check("limit switch end: error word 26", s["error"] == 26, s)
        check("stopped behind the switch at 60 mm", 60000 <= s["actual"] < 100000, s)
        check("BA7 forward again: direction locked (26)", link.send("X", 1, 0, [0x0700, 0] + dd(1000) + [0x0004]) == 0
              and status(link)["error"] == 26)
        check("BA7 backward 20 mm leaves the switch", link.send("X", 1, 0, [0x0700, 0] + dd(20000) + [0x0008]) == 0)
        s, _ = wait_finished(link)
        check("moved back without error", s["error"] == 0 and s["actual"] < 60000, s)
        if MACHINE:
            time.sleep(0.5)  # the plant settles on the last pulse
            p.stdin.write("machine\n")
            p.stdin.flush()
            line = p.stdout.readline().strip()
            words = line.split()
            pos = int(words[4]) if len(words) > 5 and words[3] == "position" else None
            check("machine axis where the module's pulses put it (10 um/pulse)",
                  pos is not None and abs(pos * 10 - s["actual"]) <= 10 and "standstill" in line,
                  f"{line!r}, module actual {s['actual']} BU")
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
