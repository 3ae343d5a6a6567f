#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# CLI end to end: `hilbridge download/upload clm14` against `hilbridge emulate clm14` on a pty, with
# the verbs of CiA 301 / STEP 7 (docs/cli.md): download = file -> device, upload = device -> file.
# An invalid file sends nothing; a download interrupted by a line that stops answering reports
# exactly what reached the device, leaves a resume journal, and `--resume` completes and
# verifies it; an upload keeps the previous file as .bak; the emulator's state survives a restart.
# The verb swap is safe for old scripts: an old-style `upload DEVICE FILE` (meant: send) and
# `download DEVICE FILE` (meant: read) never write the device nor the file.
import os
import pty
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
    # stdin is not a terminal: `download` sends only with --yes
    return subprocess.run([HIL, *args], capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)


def run_on_terminal(answer, *args):
    """`hilbridge ARGS` with a terminal on stdin, typing `answer` at the confirmation."""
    master, slave = pty.openpty()
    try:
        p = subprocess.Popen([HIL, *args], stdin=slave, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        os.write(master, (answer + "\n").encode())
        out, err = p.communicate(timeout=60)
        return p.returncode, out, err
    finally:
        os.close(master)
        os.close(slave)


def device_program(port, d, name):
    """The emulator's program lines as `upload` reads them."""
    out = os.path.join(d, name)
    r = run("upload", "clm14", "--port", port, "--what", "program", "--out", out)
    return r, [l for l in open(out).read().splitlines() if not l.startswith(";")] if r.returncode == 0 else []


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
        r = run("download", "clm14", "--port", emu.path, bad, "--yes")
        check("invalid file: exit 2", r.returncode == 2, r.stderr)
        check("invalid file: problem with line", "bad.prg:3:" in r.stderr and "nothing was sent" in r.stderr, r.stderr)
        r = run("upload", "clm14", "--port", emu.path, "--what", "program", "--out", os.path.join(d, "x.prg"))
        check("nothing of the invalid file reached the device", "0000" not in open(os.path.join(d, "x.prg")).read().split("\n", 2)[2], r.stdout)

        check("drop command", emu.command("drop 20 100000").startswith("ok"))
        r = run("download", "clm14", "--port", emu.path, "--timeout", "100ms", "--retries", "0", prog, "--yes")
        check("interrupted download: exit 1", r.returncode == 1, r.stderr)
        check("interrupted download: exact report",
              "confirmed 0000..0019 (20 items); 0020 was sent but not confirmed" in r.stderr and "39 item(s) not sent" in r.stderr,
              r.stderr)
        check("resume journal written", os.path.exists(prog + ".hilbridge-resume"))
        emu.command("drop 0 0")
        r = run("download", "clm14", "--port", emu.path, "--resume", prog, "--yes")
        check("resumed download: exit 0", r.returncode == 0, r.stderr + r.stdout)
        check("resumed at item 20", "resuming at item 20" in r.stdout, r.stdout)
        check("verified after resume", "verified" in r.stdout, r.stdout)
        check("journal removed", not os.path.exists(prog + ".hilbridge-resume"))

        out = os.path.join(d, "back.prg")
        with open(out, "w") as f:
            f.write("old content\n")
        r = run("upload", "clm14", "--port", emu.path, "--what", "program", "--out", out)
        check("upload: exit 0", r.returncode == 0, r.stderr)
        check("upload: old file kept as .bak", open(out + ".bak").read() == "old content\n")
        lines = [l for l in open(out).read().splitlines() if not l.startswith(";")]
        check("upload: 60 program lines", len(lines) == 60 and lines[59] == "0059 WAI 59.500", lines[-1:])

        # The verb swap, as old scripts meet it. A stale 10-line backup that an old nightly
        # `download DEVICE backup.prg` would have refreshed must never reach the device.
        backup = os.path.join(d, "backup.prg")
        with open(backup, "w") as f:
            f.write("; hilbridge clm14 program\n")
            for i in range(10):
                f.write(f"{i:04d} WAI 01.000\n")
        before = open(backup).read()
        r = run("download", "clm14", "--port", emu.path, "--what", "program", backup)
        check("old-style download over an existing file: exit 2 without --yes", r.returncode == 2, r.stderr)
        check("old-style download: explains the swap and the --yes",
              "--yes" in r.stderr and "upload DEVICE --out FILE" in r.stderr, r.stderr)
        check("old-style download: file untouched", open(backup).read() == before and not os.path.exists(backup + ".bak"))
        r, lines = device_program(emu.path, d, "check1.prg")
        check("old-style download: the device still has its 60 lines", len(lines) == 60 and lines[0] == "0000 WAI 00.500",
              lines[:2])
        missing = os.path.join(d, "new-backup.prg")
        r = run("download", "clm14", "--port", emu.path, "--what", "program", missing, "--yes")
        check("download of a file that does not exist: exit 2", r.returncode == 2, r.stderr)
        check("download of a missing file: explains, names upload --out",
              "does not exist" in r.stderr and f"--out {missing}" in r.stderr and not os.path.exists(missing), r.stderr)
        r = run("upload", "clm14", "--port", emu.path, prog)
        check("old-style upload DEVICE FILE: exit 2", r.returncode == 2, r.stderr)
        check("old-style upload: refused with the swap and the new spelling",
              "refused" in r.stderr and f"hilbridge download clm14 ... {prog} --yes" in r.stderr, r.stderr)
        r = run("upload", "clm14", "--port", emu.path, "--resume", "--out", os.path.join(d, "r.prg"))
        check("upload --resume (a download option): exit 2, nothing written",
              r.returncode == 2 and not os.path.exists(os.path.join(d, "r.prg")), r.stderr)
        r = run("upload", "clm14", "--port", emu.path)
        check("upload without --out: exit 2", r.returncode == 2 and "--out FILE is required" in r.stderr, r.stderr)
        rc, out_, err = run_on_terminal("n", "download", "clm14", "--port", emu.path, "--what", "program", backup)
        check("download on a terminal, answered n: exit 2, not sent", rc == 2 and "not confirmed" in err, err)
        r, lines = device_program(emu.path, d, "check2.prg")
        check("answered n: the device still has its 60 lines", len(lines) == 60, lines[:2])
        rc, out_, err = run_on_terminal("y", "download", "clm14", "--port", emu.path, "--what", "program", backup)
        check("download on a terminal, answered y: sent and verified", rc == 0 and "verified" in out_, err + out_)
        r, lines = device_program(emu.path, d, "check3.prg")
        check("answered y: the device has the 10 new lines", len(lines) == 60 and lines[9] == "0009 WAI 01.000", lines[:10])
        r = run("download", "clm14", "--port", emu.path, prog, "--yes")
        check("download --yes puts the 60 lines back", r.returncode == 0, r.stderr)
    finally:
        emu.close()
    # Restart: the state file brings the program back.
    emu = Emulator(HIL, "--mode", "parameter", "--state", state)
    try:
        r = run("upload", "clm14", "--port", emu.path, "--what", "program", "--out", os.path.join(d, "again.prg"))
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
        r = run("upload", "clm14", "--port", addr, "--what", "program", "--out", out)
        check("a well-behaved TCP client is served after the idle one", r.returncode == 0, r.stderr)
    finally:
        tcp.stdin.write("quit\n")
        tcp.stdin.flush()
        tcp.wait(timeout=10)

# Wrong peer and false success: ports are range-checked, never cast to another port; a download
# of DBs the file does not hold sends nothing and fails.
r = run("download", "clm14", "--port", "tcp:127.0.0.1:99999", "examples/serial/clm14-feed.prg", "--yes")
check("tcp port 99999 refused", r.returncode != 0 and "not a TCP port number 1..65535" in r.stderr, r.stderr)
r = run("emulate", "clm14", "--tcp", "70000")
check("emulate --tcp 70000 refused", r.returncode != 0 and "70000" in r.stderr, r.stderr)
for dev in ("ip247", "wf725"):
    f = "examples/serial/ip247-md-db1.s5db" if dev == "ip247" else "examples/serial/wf725-md-defaults.s5db"
    r = run("download", dev, "--port", "tcp:127.0.0.1:9", "--db", "7", f, "--yes")
    check(f"download {dev} --db 7 with no DB7: exit 2", r.returncode == 2, r.stderr + r.stdout)
    check(f"download {dev} --db 7: says so, sends nothing",
          "DB7 not in" in r.stderr and "nothing was sent" in r.stderr and "verified" not in r.stdout, r.stderr)

sys.exit(1 if failures else 0)
