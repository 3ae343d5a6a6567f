#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# CLI end to end: `hilbridge upload/download clm14` against `hilbridge emulate clm14` on a pty:
# an invalid file sends nothing; an upload interrupted by a line that stops answering reports
# exactly what reached the device, leaves a resume journal, and `--resume` completes and
# verifies it; a download keeps the previous file as .bak; the emulator's state survives a restart.
import os
import socket
import subprocess
import sys
import tempfile

from clm14_emulator import Emulator  # beside this file

HIL = sys.argv[1]
failures = []


def check(name, cond, detail=""):
    print(("ok   " if cond else "FAIL ") + name + ("" if cond else f": {detail}"))
    if not cond:
        failures.append(name)


def run(*args):
    return subprocess.run([HIL, *args], capture_output=True, text=True, timeout=60)


with tempfile.TemporaryDirectory() as d:
    state = os.path.join(d, "clm.json")
    prog = os.path.join(d, "p.prg")
    with open(prog, "w") as f:
        f.write("; hilbridge clm14 program\n")
        for i in range(60):
            f.write(f"{i:04d} WAI {i % 60:02d}.500\n")
    emu = Emulator(HIL, "--mode", "parameter", "--state", state)
    try:
        bad = os.path.join(d, "bad.prg")
        with open(bad, "w") as f:
            f.write("; hilbridge clm14 program\n0000 WAI 00.500\n0001 FOO 1\n")
        r = run("upload", "clm14", "--port", emu.path, bad)
        check("invalid file: exit 2", r.returncode == 2, r.stderr)
        check("invalid file: problem with line", "bad.prg:3:" in r.stderr and "nothing was sent" in r.stderr, r.stderr)
        r = run("download", "clm14", "--port", emu.path, "--what", "program", os.path.join(d, "x.prg"))
        check("nothing of the invalid file reached the device", "0000" not in open(os.path.join(d, "x.prg")).read().split("\n", 2)[2], r.stdout)

        check("drop command", emu.command("drop 20 100000").startswith("ok"))
        r = run("upload", "clm14", "--port", emu.path, "--timeout", "100ms", "--retries", "0", prog)
        check("interrupted upload: exit 1", r.returncode == 1, r.stderr)
        check("interrupted upload: exact report",
              "confirmed 0000..0019 (20 items); 0020 was sent but not confirmed" in r.stderr and "39 item(s) not sent" in r.stderr,
              r.stderr)
        check("resume journal written", os.path.exists(prog + ".hilbridge-resume"))
        emu.command("drop 0 0")
        r = run("upload", "clm14", "--port", emu.path, "--resume", prog)
        check("resumed upload: exit 0", r.returncode == 0, r.stderr + r.stdout)
        check("resumed at item 20", "resuming at item 20" in r.stdout, r.stdout)
        check("verified after resume", "verified" in r.stdout, r.stdout)
        check("journal removed", not os.path.exists(prog + ".hilbridge-resume"))

        out = os.path.join(d, "back.prg")
        with open(out, "w") as f:
            f.write("old content\n")
        r = run("download", "clm14", "--port", emu.path, "--what", "program", out)
        check("download: exit 0", r.returncode == 0, r.stderr)
        check("download: old file kept as .bak", open(out + ".bak").read() == "old content\n")
        lines = [l for l in open(out).read().splitlines() if not l.startswith(";")]
        check("download: 60 program lines", len(lines) == 60 and lines[59] == "0059 WAI 59.500", lines[-1:])
    finally:
        emu.close()
    # Restart: the state file brings the program back.
    emu = Emulator(HIL, "--mode", "parameter", "--state", state)
    try:
        r = run("download", "clm14", "--port", emu.path, "--what", "program", os.path.join(d, "again.prg"))
        again = [l for l in open(os.path.join(d, "again.prg")).read().splitlines() if not l.startswith(";")]
        check("state survives an emulator restart", len(again) == 60, r.stderr)
    finally:
        emu.close()

# Two emulators on one state file would overwrite each other's state: the second is refused.
# On TCP an idle client is closed after --idle-timeout, so a well-behaved one gets the line.
with tempfile.TemporaryDirectory() as d:
    state = os.path.join(d, "shared.json")
    first = Emulator(HIL, "--state", state)
    try:
        r = run("emulate", "clm14", "--pty", "--state", state)
        check("second emulator on the same state file refused", r.returncode == 2 and "in use by another process" in r.stderr,
              r.stderr)
    finally:
        first.close()
    tcp = subprocess.Popen([HIL, "emulate", "clm14", "--tcp", "0", "--idle-timeout", "500ms", "--state", "none",
                            "--mode", "parameter"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    try:
        addr = tcp.stdout.readline().strip()
        check("emulator on tcp", addr.startswith("tcp:127.0.0.1:"), addr)
        port = int(addr.rsplit(":", 1)[1])
        idle = socket.create_connection(("127.0.0.1", port))
        idle.settimeout(5)
        closed = idle.recv(1) == b""  # the emulator closes it after 0.5 s of silence
        check("idle TCP client closed after --idle-timeout", closed)
        idle.close()
        out = os.path.join(d, "tcp.prg")
        r = run("download", "clm14", "--port", addr, "--what", "program", out)
        check("a well-behaved TCP client is served after the idle one", r.returncode == 0, r.stderr)
    finally:
        tcp.stdin.write("quit\n")
        tcp.stdin.flush()
        tcp.wait(timeout=10)

# Wrong peer and false success: ports are range-checked, never cast to another port; an upload
# of DBs the file does not hold sends nothing and fails.
r = run("upload", "clm14", "--port", "tcp:127.0.0.1:99999", "examples/serial/clm14-feed.prg")
check("tcp port 99999 refused", r.returncode != 0 and "not a TCP port number 1..65535" in r.stderr, r.stderr)
r = run("emulate", "clm14", "--tcp", "70000")
check("emulate --tcp 70000 refused", r.returncode != 0 and "70000" in r.stderr, r.stderr)
for dev in ("ip247", "wf725"):
    f = "examples/serial/ip247-md-db1.s5db" if dev == "ip247" else "examples/serial/wf725-md-defaults.s5db"
    r = run("upload", dev, "--port", "tcp:127.0.0.1:9", "--db", "7", f)
    check(f"upload {dev} --db 7 with no DB7: exit 2", r.returncode == 2, r.stderr + r.stdout)
    check(f"upload {dev} --db 7: says so, sends nothing",
          "DB7 not in" in r.stderr and "nothing was sent" in r.stderr and "verified" not in r.stdout, r.stderr)

sys.exit(1 if failures else 0)
