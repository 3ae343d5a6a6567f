#!/usr/bin/python3
# SPDX-License-Identifier: MIT
# A Python script as the S5 PLC against `hilbridge emulate ip247` over its pty (python3-serial;
# 3964R and RK512 from the notes in s5_plc_link.py, no hilbridge code on this side): write an MD
# DB and a traversing-program DB, select automatic and start, read the actual value while the
# axis moves, run data jobs through the job block DX 4 (BA70 SYS-ID, BA67 read MD, BA66 actual
# values while the axis moves) into the PLC's DBs DX 50/51, drive into the "end" limit switch and
# read the error word. Run by ctest; exit 77 = skipped (python3-serial missing).
import subprocess
import sys
import time

from plc_check import check, finish, stop  # verdicts, the emulator's end

try:
    from s5_plc_link import Link, dd, s32  # 3964R + RK512, the PLC side (python3-serial)
    from ip247_plc import md_db, vp_db, status, wait_finished, data_job
except ImportError:
    print("SKIP: python3-serial is not installed (apt-get install python3-serial)")
    sys.exit(77)

HILBRIDGE = sys.argv[1]
# Optional: `--machine FILE`: the emulator's axis 1 drives the machine axis of FILE (retrofit mode);
# the script then also checks that the machine axis stands where the module's pulses put it.
MACHINE = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--machine" else None


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
        check("MD DB1 accepted", link.send(1, 0, md_db(1)) == 0)
        err, back = link.fetch(1, 0, 70)
        check("MD DB1 read back", err == 0 and back == md_db(1), f"{err} {back[:6]}")
        prog = "%10 PLC\nN10 X50 F3000 M10\nN20 G04 F2\nN30 X0 F3000 M20\nN40 M02\n"
        check("VP DB10 accepted", link.send(10, 0, vp_db(10, prog)) == 0)
        check("VP DB10 again: no overwrite (07)", link.send(10, 0, vp_db(10, prog)) == 0x07)
        bad = "%11\nN10 X1 F10 M100\nN20 M02\n"
        check("faulty VP DB11 rejected (10h)", link.send(11, 0, vp_db(11, bad)) == 0x10)
        check("faulty VP DB11 not stored", link.fetch(11, 0, 5)[0] == 0x08)
        s = status(link)
        check("reference missing before BA5", s["attr"] & 0x20 != 0, s)
        check("BA5 set reference", link.send(1, 0, [0x0501, 0, 0, 0, 0x0001], typ="X") == 0)
        s = status(link)
        check("reference set", s["attr"] & 0x20 == 0 and s["error"] == 0, s)
        check("BA8 program 10 start", link.send(1, 0, [0x080A, 0, 0, 0, 0x0001], typ="X") == 0)
        s, samples = wait_finished(link)
        moving = [x["actual"] for x in samples if 0 < x["actual"] < 50000]
        check("actual values read while moving", len(moving) >= 3, [x["actual"] for x in samples][:20])
        check("M10 seen while running", any(x["m"] == 10 for x in samples))
        check("program end: actual 0, M02, no error", s["actual"] == 0 and s["m"] == 2 and s["error"] == 0, s)
        # Data jobs (DX 4) into the PLC's own DBs (DX 50, 51), created by the PLC first.
        w = data_job(link, 70, z_db=50, ssnr=3)
        check("BA70 into a DB the PLC has not created: MB250 8", w[0] == 0 and w[7] >> 8 == 8 and w[6] & 2, w[:10])
        check("PLC DB50 created (DX 50)", link.send(50, 0, [0] * 9, typ="X") == 0)
        w = data_job(link, 70, z_db=50, ssnr=3)
        err, sysid = link.fetch(50, 0, 9, typ="X")
        check("BA70 SYS-ID: done, 9 words, 'IP' '24' '7 '", w[0] == 0 and w[6] == 0 and w[9] == 9 and err == 0
              and sysid[:3] == [0x4950, 0x3234, 0x3720], (w[:10], [hex(x) for x in sysid]))
        check("PLC DB51 created (70 words)", link.send(51, 0, [0] * 70, typ="X") == 0)
        w = data_job(link, 67, q_db=1, z_db=51, ssnr=0)
        err, md = link.fetch(51, 0, 70, typ="X")
        check("BA67 reads the MD DB1 of axis 1 into DB51", w[0] == 0 and w[6] == 0 and md == md_db(1), w[:10])
        w = data_job(link, 22, q_db=50, z_db=12, ssnr=0)
        check("BA22 on an axis tile: module error 46", w[7] & 0xFF == 46 and w[6] & 1, w[:10])
        check("BA7 forward 100 mm", link.send(1, 0, [0x0700, 0] + dd(100000) + [0x0004], typ="X") == 0)
        time.sleep(0.3)
        w = data_job(link, 66, z_db=50, ssnr=0)
        err, av = link.fetch(50, 0, 6, typ="X")
        actual, remaining = s32(av[0], av[1]), s32(av[4], av[5])
        check("BA66 while the axis moves: actual + remaining = 100 mm", w[0] == 0 and w[6] == 0 and
              0 < actual < 60000 and actual + remaining == 100000, (w[:10], actual, remaining))
        s, _ = wait_finished(link)
        check("limit switch end: error word 26", s["error"] == 26, s)
        check("stopped behind the switch at 60 mm", 60000 <= s["actual"] < 100000, s)
        check("BA7 forward again: direction locked (26)", link.send(1, 0, [0x0700, 0] + dd(1000) + [0x0004], typ="X") == 0
              and status(link)["error"] == 26)
        check("BA7 backward 20 mm leaves the switch", link.send(1, 0, [0x0700, 0] + dd(20000) + [0x0008], typ="X") == 0)
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
        stop(p)
    finish()


main()
