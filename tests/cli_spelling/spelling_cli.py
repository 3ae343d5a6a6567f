# SPDX-License-Identifier: MIT
"""The CLI's spellings as a user types them (docs/cli.md, "Changed spellings"): the real binary, no
hardware. `durations`: every time option takes a unit (250ms, 2s, 30us, 1min); a bare number keeps the
option's old unit with a one-line deprecation warning naming the spelling to use; renamed options
keep their old name as a hidden alias that warns; a bad value exits 2 naming the option and what is
expected.
Usage: /usr/bin/python3 spelling_cli.py HILBRIDGE durations (run from the source tree's root)."""
import re
import subprocess
import sys

c_failed = 0
c_passed = 0


def check(cond, what):
    global c_failed, c_passed
    if cond:
        c_passed += 1
    else:
        c_failed += 1
        print(f"FAIL: {what}", flush=True)


def run(hb, *args, timeout=60):
    p = subprocess.run([hb, *args], capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def warnings(err):
    return [line for line in err.splitlines() if "warning:" in line]


def expect_ok_quiet(hb, args, what, rc_wanted=0):
    """Runs with the new spelling: the wanted exit status and no deprecation warning."""
    rc, out, err = run(hb, *args)
    check(rc == rc_wanted, f"{what}: exit {rc}, expected {rc_wanted}: {err}")
    check(not [w for w in warnings(err) if "deprecated" in w], f"{what}: no deprecation warning: {err}")
    return rc, out, err


def expect_warning(hb, args, wanted, what, rc_wanted=0):
    """Runs with an old spelling: it still works, and warns once with the new spelling."""
    rc, out, err = run(hb, *args)
    check(rc == rc_wanted, f"{what}: exit {rc}, expected {rc_wanted}: {err}")
    w = [x for x in warnings(err) if "deprecated" in x]
    check(len(w) == 1 and wanted in w[0], f"{what}: one warning naming {wanted!r}: {err}")
    return rc, out, err


def expect_usage(hb, args, pieces, what):
    """A bad value: exit 2 and a message naming the option, the value and what is expected."""
    rc, out, err = run(hb, *args)
    check(rc == 2, f"{what}: exit {rc}, expected 2: {err}")
    for p in pieces:
        check(p in err, f"{what}: {p!r} in the message: {err}")


class Proc:
    """A background hilbridge process whose first stdout line matches `pattern`."""

    def __init__(self, args, pattern):
        self.p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.p.stdout.readline()
        self.m = re.search(pattern, line)
        if not self.m:
            self.p.kill()
            out, err = self.p.communicate(timeout=5)
            sys.exit(f"{args[1:3]} did not start: {line!r} {out!r} {err!r}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.p.poll() is None:
            self.p.kill()
        self.err = self.p.communicate(timeout=10)[1]


def hub(hb, *extra):
    return Proc([hb, "can", "hub", "--listen", "127.0.0.1:0", *extra], r"socketcand://127\.0\.0\.1:(\d+)/can0")


def check_durations(hb):
    # latency: --duration (was --seconds) and --period
    expect_ok_quiet(hb, ["latency", "--duration", "50ms", "--period", "1ms"], "latency --duration 50ms")
    expect_warning(hb, ["latency", "--seconds", "0.05"], "--seconds is deprecated; write --duration 0.05s",
                   "latency --seconds (old name)")
    expect_warning(hb, ["latency", "--duration", "0.05"], "write --duration 0.05s", "latency bare number = seconds")
    expect_usage(hb, ["latency", "--duration", "fast"],
                 ["--duration", "'fast' is not a duration", "us, ms, s or min"], "latency --duration fast")
    expect_usage(hb, ["latency", "--period", "10us"], ["--period", "10us is out of range", "50us .. 1s"],
                 "latency --period 10us")
    expect_usage(hb, ["latency", "--duration", "-1s"], ["--duration", "not a duration"], "negative duration")
    expect_usage(hb, ["run", "--virtual", "--duration", "1h"], ["--duration", "'1h' is not a duration"],
                 "run --duration with an unknown unit")

    # CAN: hub --latency/--join-hold, dump --duration, send --interval, scan/sdo --timeout
    with hub(hb, "--latency", "30us", "--join-hold", "0ms") as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        expect_ok_quiet(hb, ["can", "dump", "--bus", bus, "--duration", "300ms", "-q"], "can dump --duration 300ms")
        expect_warning(hb, ["can", "dump", "--bus", bus, "--duration", "0.3", "-q"], "write --duration 0.3s",
                       "can dump bare seconds")
        expect_usage(hb, ["can", "dump", "--bus", bus, "--duration", "0s"], ["--duration", "out of range"],
                     "can dump --duration 0s")
        expect_ok_quiet(hb, ["can", "send", "--bus", bus, "--interval", "5ms", "701#05", "702#05"], "can send --interval")
        expect_warning(hb, ["can", "send", "--bus", bus, "--interval-ms", "5", "701#05", "702#05"],
                       "--interval-ms is deprecated; write --interval 5ms", "can send --interval-ms (old name)")
        expect_ok_quiet(hb, ["scan", "--bus", bus, "--timeout", "100ms"], "scan --timeout 100ms")
        expect_warning(hb, ["scan", "--bus", bus, "--timeout", "100"], "write --timeout 100ms", "scan bare ms")
        expect_usage(hb, ["sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "11min"],
                     ["--timeout", "11min is out of range", "1ms .. 10min"], "sdo --timeout too long")
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5", "--duration", "20s"], r"node 5 up"):
            rc, out, err = expect_ok_quiet(hb, ["sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "2s"],
                                           "sdo read --timeout 2s")
            expect_warning(hb, ["sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "2000"],
                           "write --timeout 2000ms", "sdo read bare ms")
        rc, _, err = run(hb, "emulate", "cia402", "--bus", bus, "--node", "6", "--duration", "200ms")
        check(rc == 0, f"emulate cia402 --duration 200ms ends by itself: {rc} {err}")
    with hub(hb, "--latency-us", "30", "--join-grace-ms", "0") as h:
        pass
    check(len([w for w in warnings(h.err) if "deprecated" in w]) == 2 and "write --latency 30us" in h.err and
          "write --join-hold 0ms" in h.err, f"hub old names warn: {h.err}")

    # Modbus: client --timeout (was seconds), emulator --duration/--frame-timeout/--step-period
    expect_warning(hb, ["modbus", "read", "127.0.0.1:1", "1", "0", "--timeout", "0.2"], "write --timeout 0.2s",
                   "modbus bare seconds", rc_wanted=1)
    expect_ok_quiet(hb, ["modbus", "read", "127.0.0.1:1", "1", "0", "--timeout", "200ms"], "modbus --timeout 200ms",
                    rc_wanted=1)
    expect_usage(hb, ["modbus", "read", "127.0.0.1:1", "1", "0", "--timeout", "2min"],
                 ["--timeout", "2min is out of range", "1ms .. 1min"], "modbus --timeout too long")
    rc, out, err = expect_ok_quiet(hb, ["emulate", "modbus-drive", "--listen", "127.0.0.1:0", "--duration", "300ms",
                                        "--frame-timeout", "1s", "--step-period", "2ms"], "modbus-drive with units")
    check("stopped" in out, f"modbus-drive stops after --duration: {out}")
    expect_warning(hb, ["emulate", "modbus-drive", "--listen", "127.0.0.1:0", "--duration", "300ms",
                        "--step-period-ms", "2"], "--step-period-ms is deprecated; write --step-period 2ms",
                   "modbus-drive --step-period-ms (old name)")

    # Serial links: --timeout (was --timeout-ms), emulators --idle-timeout and --cycle
    expect_usage(hb, ["download", "clm14", "--port", "/dev/null", "--timeout", "5ms", "README.md", "--yes"],
                 ["--timeout", "5ms is out of range", "10ms .. 10min"], "serial --timeout too short")
    expect_usage(hb, ["emulate", "clm14", "--tcp", "0", "--idle-timeout", "10ms"],
                 ["--idle-timeout", "out of range", "100ms .. 1440min"], "emulate --idle-timeout too short")
    with Proc([hb, "emulate", "ip247", "--pty", "--cycle-ms", "2", "--state", "none"], r"/dev/pts/\d+") as p:
        pass
    check("--cycle-ms is deprecated; write --cycle 2ms" in p.err, f"emulate ip247 --cycle-ms warns: {p.err}")
    with Proc([hb, "emulate", "ip247", "--pty", "--cycle", "2ms", "--state", "none"], r"/dev/pts/\d+") as p:
        pass
    check("deprecated" not in p.err, f"emulate ip247 --cycle 2ms: {p.err}")

    # --help shows the new spellings only
    rc, out, _ = run(hb, "can", "send", "--help")
    check("--interval" in out and "--interval-ms" not in out, f"can send --help: {out}")
    rc, out, _ = run(hb, "latency", "--help")
    check("--duration" in out and "--seconds" not in out, f"latency --help: {out}")


def main():
    hb, part = sys.argv[1], sys.argv[2]
    {"durations": check_durations}[part](hb)
    print(f"{c_passed} passed, {c_failed} failed")
    sys.exit(1 if c_failed or not c_passed else 0)


if __name__ == "__main__":
    main()
