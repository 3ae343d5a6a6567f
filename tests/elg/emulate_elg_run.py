#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# `hilbridge emulate elg-tape --program` end to end, seen from its serial line alone (Debian's
# python3-serial on the pty) and its console: the annex program runs on the emulator's real time in
# retrofit mode (--machine: the ELG's axes built from a machine file on their transports), Data
# Start (DC2) while coupled punches nothing and raises 2214, Data Start uncoupled punches the MD
# tape, the PC data channel reads the running model, and a machine file whose scaling differs
# from the tape's MD is refused. Run by ctest from the source tree; exit 77 = skipped.
import os
import subprocess
import sys
import tempfile
import time

try:
    import serial  # python3-serial
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
TAPE = "examples/controllers/elg-hobbing.tape.txt"
PROGRAM = "examples/controllers/elg-annex.nc"
MACHINE = "tests/elg/data/elg-machine.yaml"
failures = []


def check(name, ok, detail=""):
    if ok:
        print(f"ok   {name}")
    else:
        failures.append(f"{name}: {detail}")
        print(f"FAIL {name}: {detail}")


class Emulator:
    def __init__(self, *args):
        self.p = subprocess.Popen([HILBRIDGE, "emulate", "elg-tape", "--pty", "--state", "none", *args],
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.path = self.p.stdout.readline().strip()

    def command(self, line):
        self.p.stdin.write(line + "\n")
        self.p.stdin.flush()
        return self.p.stdout.readline().strip()

    def wait_for(self, text, seconds):
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            status = self.command("status")
            if text in status:
                return status
            time.sleep(0.02)
        return self.command("status")

    def close(self):
        self.p.stdin.write("quit\n")
        self.p.stdin.flush()
        self.p.wait(timeout=10)


# A machine file with another scaling than the tape's MD: refused, exit 2, the axis named.
with tempfile.TemporaryDirectory() as tmp:
    other = os.path.join(tmp, "machine.yaml")
    with open(other, "w") as f:
        f.write(open(MACHINE).read().replace("inc_per_unit: 2000, limits: {velocity: 166",
                                             "inc_per_unit: 1000, limits: {velocity: 166", 1))
    bad = subprocess.run([HILBRIDGE, "emulate", "elg-tape", "--pty", "--state", "none", "--tape", TAPE, "--program",
                          PROGRAM, "--machine", other], capture_output=True, text=True, timeout=20)
check("scaling mismatch refused", bad.returncode == 2 and "axis C" in bad.stderr, f"{bad.returncode} {bad.stderr}")
missing = subprocess.run([HILBRIDGE, "emulate", "elg-tape", "--pty", "--state", "none", "--program", PROGRAM],
                         capture_output=True, text=True, timeout=20)
check("--program needs --tape", missing.returncode == 2 and "--tape" in missing.stderr, missing.stderr)

emu = Emulator("--tape", TAPE, "--program", PROGRAM, "--machine", MACHINE)
try:
    check("pty", emu.path.startswith("/dev/pts/"), emu.path)
    port = serial.Serial(emu.path, 4800, bytesize=8, parity="N", stopbits=2, timeout=0.5)
    status = emu.wait_for("coupled 1", 10)
    check("the program couples C", "coupled 1" in status, status)
    port.reset_input_buffer()
    port.write(b"\x12")  # Data Start while coupled
    time.sleep(0.3)
    check("nothing punched while coupled", port.read(200) == b"")
    alarm = emu.command("alarm")
    check("alarm 2214", "2214" in alarm, alarm)
    reply = emu.command("pc read 27 1")
    check("data channel: alarm slot 1", reply == "ok 2214", reply)
    reply = emu.command("pc read 12 2")
    check("data channel: actual value of C", reply.startswith("ok "), reply)
    reply = emu.command("pc write 10 2801 12000")
    check("data channel: MD locked while coupled", "3016" in reply, reply)
    status = emu.wait_for("coupled 0", 30)
    check("Gearing OFF", "coupled 0" in status, status)
    port.write(b"\x12")  # Data Start uncoupled: the MD tape
    tape = b""
    end = time.monotonic() + 5
    while time.monotonic() < end and b"\x4d\x30\xb2" not in tape:  # M02 in ISO
        tape += port.read(256)
    text = bytes(b & 0x7F for b in tape).decode("ascii", "replace")
    check("MD tape punched", "%TEA1" in text and "N3961=180000" in text, text[:120])
    emu.command("reset")
    time.sleep(0.2)
finally:
    emu.close()

if failures:
    print("\n".join(failures))
    sys.exit(1)
