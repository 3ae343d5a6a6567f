#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# Status 47 (master encoder 1) and 45/49 (analog inputs) of `hilbridge emulate clm14` come from the
# running model, seen over the serial protocol alone (python3-serial, checksums computed here):
# with C002 = 0 status 47 is serial error 10; with a measuring wheel (C000 1250, C002 20 IU) and
# the material running at 40 IU/s (console `material 40`, the unit's hardware) it reads the
# wheel's 120 rpm, and again 0 when the material stops; the analog inputs set on the console
# (`analog N MV`) read back in mV on statuses 49 (AE1/AE2) and 45 (AE3/AE4). Exit 77 = skipped.
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


emu = Emulator(HILBRIDGE, "--mode", "parameter", "--state", "none")
try:
    port = serial.Serial(emu.path, 19200, bytesize=8, parity="N", stopbits=1, timeout=2)

    def ask(text: str) -> bytes:
        port.write(telegram(text))
        return port.read_until(b"\n")

    def status(n: str) -> bytes:
        return ask(f"? X  {n} ")

    # master encoder 1 not used: status 47 is "M-Wheel Param Error" (serial error 10)
    check("C002 = 0", ask("# K C002 0000.00000") == b"Y\r\n")
    check("mode manual", emu.command("mode manual") == "ok mode manual")
    time.sleep(0.1)
    r = status("47")
    check("status 47 without a wheel: serial error 10", r.startswith(b"X 01 10"), repr(r))
    check("material without a wheel is refused", emu.command("material 40").startswith("error:"))
    # a measuring wheel: 1250 lines (x4) on 20 IU per revolution
    check("mode parameter", emu.command("mode parameter") == "ok mode parameter")
    for number, data in (("C000", "01250 0000"), ("C002", "0020.00000")):
        check(f"parameter {number}", ask(f"# K {number} {data}") == b"Y\r\n")
    check("mode manual", emu.command("mode manual") == "ok mode manual")
    time.sleep(0.1)
    check("standing material: 0 rpm", status("47") == telegram("X 47 0 +0000.00 "), repr(status("47")))
    check("material 40 IU/s", emu.command("material 40") == "ok material 40")
    time.sleep(1.0)
    check("40 IU/s on a 20 IU wheel: 120 rpm", status("47") == telegram("X 47 0 +0120.00 "), repr(status("47")))
    check("material stops", emu.command("material 0") == "ok material 0")
    time.sleep(1.0)
    check("stopped: 0 rpm", status("47") == telegram("X 47 0 +0000.00 "), repr(status("47")))
    check("material -10 IU/s", emu.command("material -10") == "ok material -10")
    time.sleep(1.0)
    check("reverse: -30 rpm", status("47") == telegram("X 47 0 -0030.00 "), repr(status("47")))
    # analog inputs
    check("analogs read 0", status("49") == telegram("X 49 +00000 +00000 "), repr(status("49")))
    for cmd in ("analog 1 5000", "analog 2 -123", "analog 4 -10000", "analog 3 42"):
        check(cmd, emu.command(cmd) == "ok " + cmd)
    check("analog out of range refused", emu.command("analog 2 10001").startswith("error:"))
    time.sleep(0.1)
    check("status 49: AE1, AE2", status("49") == telegram("X 49 +05000 -00123 "), repr(status("49")))
    check("status 45: AE3, AE4", status("45") == telegram("X 45 +00042 -10000 "), repr(status("45")))
    port.close()
finally:
    emu.close()

if failures:
    print("\n".join("FAIL " + f for f in failures))
    sys.exit(1)
print("all status 45/47/49 checks passed")
