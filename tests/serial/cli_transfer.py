#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# CLI end to end: `hilbridge upload/download clm14` against `hilbridge emulate clm14` on a pty:
# an invalid file sends nothing; an upload interrupted by a line that stops answering reports
# exactly what reached the device, leaves a resume journal, and `--resume` completes and
# verifies it; a download keeps the previous file as .bak; the emulator's state survives a restart.
import os
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
        r = run("upload", "clm14", "--port", emu.path, "--timeout-ms", "100", "--retries", "0", prog)
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

sys.exit(1 if failures else 0)
