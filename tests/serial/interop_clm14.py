#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Interop test with an independent peer: Debian's python3-serial talks to `hilbridge emulate
# clm14` over its pty and checks the reply bytes against the manual's telegrams (checksums
# computed here, independently of our C++ codec). Run by ctest; exit 77 = skipped.
import sys

from clm14_emulator import Emulator  # beside this file

try:
    import serial  # python3-serial
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]


def cs(text: bytes) -> bytes:
    s = sum(text)
    x = ((s >> 8) + (s & 0xFF)) & 0xFF
    return b"$%02X" % ((-x) & 0xFF)


def telegram(text: str) -> bytes:
    t = text.encode("ascii")
    return t + cs(t) + b"\r\n"


def even(b: int) -> int:
    return b | 0x80 if bin(b & 0x7F).count("1") % 2 else b & 0x7F


failures = []


def check(name, got, want):
    if got != want:
        failures.append(f"{name}: got {got!r}, want {want!r}")
    else:
        print(f"ok   {name}")


def run_8n1():
    emu = Emulator(HILBRIDGE, "--format", "8N1", "--mode", "parameter", "--state", "none")
    try:
        port = serial.Serial(emu.path, 9600, bytesize=8, parity="N", stopbits=1, timeout=2)
        def ask(req: bytes) -> bytes:
            port.write(req)
            return port.read_until(b"\n")
        check("empty line 0000", ask(telegram("? N0000")), b"# N0000 NOP  $60\r\n")
        check("manual checksum example C0", ask(b"# N0101 AEA Q1.00.3 1 $C0\r\n"), b"Y\r\n")
        check("read back 0101", ask(telegram("? N0101")), b"# N0101 AEA Q1.00.3 1 $C0\r\n")
        check("B002 default (E4)", ask(telegram("? K B002")), b"# K B002 019200 0 1 8 1$E4\r\n")
        check("param write in Parameter mode", ask(telegram("# K A101 0020.00000")), b"Y\r\n")
        check("param read", ask(telegram("? K A101")), telegram("# K A101 0020.00000"))
        check("variable V600 (93)", ask(b"# V600 +00000100.000000 $93\r\n"), b"Y\r\n")
        check("variable read", ask(telegram("? V600")), telegram("V 600 +00000100.000000 "))
        check("checksum error -> status 01 / 04", ask(b"# N0101 AEA Q1.00.3 1 $C1\r\n"),
              telegram("X 01 04 RS Checksum Error    "))
        check("block too large -> 12", ask(telegram("? N3000")), telegram("X 01 12 Block # too large    "))
        check("console mode manual", emu.command("mode manual"), "ok mode manual")
        check("param write outside Parameter mode -> 05", ask(telegram("# K A101 0030.00000")),
              telegram("X 01 05 Invalid Mode         "))
        port.close()
    finally:
        emu.close()


def run_7e1():
    # 7E1 on a pty: the parity bit travels in bit 7 (software parity on both sides).
    emu = Emulator(HILBRIDGE, "--format", "7E1", "--mode", "parameter", "--state", "none")
    try:
        port = serial.Serial(emu.path, 9600, bytesize=8, parity="N", stopbits=1, timeout=2)
        req = bytes(even(b) for b in telegram("? N0000"))
        port.write(req)
        raw = port.read_until(bytes([even(0x0A)]))
        check("7E1 every reply byte has even parity", all(bin(b).count("1") % 2 == 0 for b in raw), True)
        check("7E1 reply content", bytes(b & 0x7F for b in raw), b"# N0000 NOP  $60\r\n")
        bad = bytearray(req)
        bad[3] ^= 0x80  # one character with wrong parity
        port.write(bytes(bad))
        raw = port.read_until(bytes([even(0x0A)]))
        check("7E1 parity error -> RS Format Error 02", bytes(b & 0x7F for b in raw),
              telegram("X 01 02 RS Format Error      "))
        port.close()
    finally:
        emu.close()


run_8n1()
run_7e1()
if failures:
    print("\n".join("FAIL " + f for f in failures))
    sys.exit(1)
print("all interop checks passed")
