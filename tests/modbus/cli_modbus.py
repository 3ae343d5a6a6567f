# SPDX-License-Identifier: MIT
"""`hilbridge modbus read|write` against `hilbridge emulate modbus-drive`: values, types, word
order, exit status and error messages.
Usage: /usr/bin/python3 cli_modbus.py HILBRIDGE"""
import subprocess
import sys

from emulator import Checks, Emulator


def run(hilbridge, *args):
    p = subprocess.run([hilbridge, *args], capture_output=True, text=True, timeout=20)
    return p.returncode, p.stdout, p.stderr


def main():
    hb = sys.argv[1]
    c = Checks()
    with Emulator(hb, "cia402") as emu:
        ep = f"127.0.0.1:{emu.port}"
        rc, out, err = run(hb, "modbus", "write", ep, "1", "2", "-123456", "--type", "i32")
        c.check(rc == 0 and "wrote 2 registers at 2 (FC 16)" in out, f"write i32: {rc} {out} {err}")
        rc, out, _ = run(hb, "modbus", "read", ep, "1", "2", "2", "--type", "hex")
        c.check(rc == 0 and out.split() == ["2:", "0xFFFE", "3:", "0x1DC0"], f"high word first on the wire: {out}")
        rc, out, _ = run(hb, "modbus", "read", ep, "1", "2", "--type", "i32")
        c.check(rc == 0 and out.strip() == "2: -123456", f"read back s32: {out}")
        rc, out, _ = run(hb, "modbus", "read", ep, "1", "2", "--type", "i32", "--word-order", "low_first")
        c.check(rc == 0 and out.strip() == f"2: {0x1DC0FFFE - (1 << 32) if 0x1DC0FFFE >= 1 << 31 else 0x1DC0FFFE}",
                f"low_first reinterprets: {out}")
        rc, out, _ = run(hb, "modbus", "write", ep, "1", "0", "0x06")
        c.check(rc == 0 and "(FC 6)" in out, f"FC6 hex value: {out}")
        rc, out, _ = run(hb, "modbus", "read", ep, "1", "10", "--type", "hex")
        c.check(rc == 0 and int(out.split()[1], 16) & 0x6F == 0x21, f"ready to switch on: {out}")
        rc, _, err = run(hb, "modbus", "write", ep, "1", "10", "1")
        c.check(rc == 1 and "exception 02 illegal data address" in err and "at 10" in err, f"read-only: {err}")
        rc, _, err = run(hb, "modbus", "read", ep, "1", "0", "1", "--input")
        c.check(rc == 1 and "FC 4" in err and "exception 02" in err, f"FC4 absent: {err}")
        rc, _, err = run(hb, "modbus", "write", ep, "1", "0", "70000")
        c.check(rc == 2 and "does not fit" in err, f"range check: {err}")
        rc, _, err = run(hb, "modbus", "write", ep, "1", "0", "1", "2", "--fc", "6")
        c.check(rc == 2 and "exactly one register" in err, f"--fc 6 with two values: {err}")
        rc, _, err = run(hb, "modbus", "read", "127.0.0.1:99999", "1", "0")
        c.check(rc == 2 and "1..65535" in err, f"bad port: {err}")
        rc, _, err = run(hb, "modbus", "read", ep, "1", "0", "--type", "f32")
        c.check(rc == 2 and "--type" in err, f"bad type: {err}")
        emu.stop()
        rc, _, err = run(hb, "modbus", "read", ep, "1", "10", "--timeout", "500ms")
        c.check(rc == 1 and "cannot connect" in err, f"server gone: {err}")
    rc, _, err = run(hb, "emulate", "modbus-drive", "--listen", "127.0.0.1:0", "--profile", "no_such_profile")
    c.check(rc == 2 and "cannot open" in err, f"bad profile: {rc} {err}")
    rc, _, err = run(hb, "emulate", "modbus-drive", "--listen", "nonsense")
    c.check(rc == 2 and "HOST:PORT" in err, f"bad listen: {rc} {err}")
    c.exit()


if __name__ == "__main__":
    main()
