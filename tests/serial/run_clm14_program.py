#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# The emulated CLM1.4 runs its program, seen over the serial protocol alone: Debian's
# python3-serial speaks the manual's telegrams (checksums computed here) to `hilbridge emulate
# clm14 --pty`, uploads parameters and a program, starts it with !START and reads positions
# (status 00), the counter (status 04), the task line (status 02) and a variable while it runs,
# and sees them change. The console only flips the mode switch (the unit's X3 inputs).
# Run by ctest; exit 77 = skipped.
import sys
import time

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


failures = []


def check(name, ok, detail=""):
    if not ok:
        failures.append(f"{name} {detail}")
    else:
        print(f"ok   {name}")


def body(reply: bytes) -> str:
    # "X 00 <content> $hh\r\n": verify the checksum, return the content after the status number
    text, _, tail = reply.rpartition(b"$")
    check_ok = cs(text) == b"$" + tail[:2]
    if not check_ok:
        failures.append(f"bad checksum in {reply!r}")
    return text.decode("ascii")


emu = Emulator(HILBRIDGE, "--mode", "parameter", "--state", "none")
try:
    port = serial.Serial(emu.path, 19200, bytesize=8, parity="N", stopbits=1, timeout=2)

    def ask(text: str) -> bytes:
        port.write(telegram(text))
        return port.read_until(b"\n")

    for number, data in (("A108", "001000"), ("A127", "M2.00.0 0000.010")):
        check(f"parameter {number}", ask(f"# K {number} {data}") == b"Y\r\n")
    program = ["COU +00000 Q1.00.4 000100", "MAT V600 = V600 + +1", "PSI 1 +000010.000 999", "JMP 0000"]
    for n, line in enumerate(program):
        check(f"program line {n:04d}", ask(f"# N{n:04d} {line} ") == b"Y\r\n")
    check("read back 0002", ask("? N0002") == telegram("# N0002 PSI 1 +000010.000 999 "))
    check("mode auto", emu.command("mode auto") == "ok mode auto")
    time.sleep(0.1)
    check("!START", ask("! START ") == b"Y\r\n")

    def sample():
        pos = body(ask("? X  00 "))      # "X 00  +00012.345  +000000.000 "
        count = body(ask("? X  04 0000 "))  # "X 04 0000 iiii zzzzzz "
        var = body(ask("? V600"))          # "V 600 +00000003.000000 "
        line = body(ask("? X  02 "))       # "X 02 nnnn uuuu "
        return float(pos.split()[2]), int(count.split()[3]), float(var.split()[2]), line

    first = sample()
    time.sleep(1.0)
    second = sample()
    print("first ", first)
    print("second", second)
    check("axis 1 moved", second[0] > first[0] + 1.0, f"{first[0]} -> {second[0]}")
    check("counter of line 0000 counts", second[1] != first[1], f"{first[1]} -> {second[1]}")
    check("V600 counts the passes", second[2] > first[2], f"{first[2]} -> {second[2]}")
    check("V600 = passes = counter", abs(second[2] - second[1]) <= 1, f"{second}")
    check("status 02 names a program line", second[3].split()[2] in ("0000", "0001", "0002", "0003"), second[3])
    check("!STOP", ask("! STOP ") == b"Y\r\n")
    time.sleep(0.5)
    stopped = sample()
    time.sleep(0.3)
    check("stopped: the position holds", abs(sample()[0] - stopped[0]) < 0.001)
    check("no error (status 53)", body(ask("? X  53 ")).startswith("X 53 00"))
    port.close()
finally:
    emu.close()

if failures:
    print("\n".join("FAIL " + f for f in failures))
    sys.exit(1)
print("all CLM program checks passed")
