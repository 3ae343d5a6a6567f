# SPDX-License-Identifier: MIT
"""The CLI's spellings as a user types them (docs/cli.md, "Changed spellings"): the real binary, no
hardware. `durations`: every time option takes a unit (250ms, 2s, 30us, 1min); a bare number keeps the
option's old unit with a one-line deprecation warning naming the spelling to use; renamed options
keep their old name as a hidden alias that warns; a bad value exits 2 naming the option and what is
expected. `exit_codes`: every command, found from the --help tree, exits 2 on an unknown option
(CLI11's parse errors included) and on a wrong value, 1 when the checked thing failed (a bus, a
server or a device that cannot be reached), 0 on success (docs/cli.md, "Exit codes").
`groups`: one grouping rule, the CANopen commands under `canopen`, the old top-level names warn.
Usage: /usr/bin/python3 spelling_cli.py HILBRIDGE durations|exit_codes|types|endpoints|groups (run from the
source tree's root)."""
import json
import os
import re
import subprocess
import sys
import tempfile

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
        expect_ok_quiet(hb, ["canopen", "scan", "--bus", bus, "--timeout", "100ms"], "scan --timeout 100ms")
        expect_warning(hb, ["canopen", "scan", "--bus", bus, "--timeout", "100"], "write --timeout 100ms",
                       "scan bare ms")
        expect_usage(hb, ["canopen", "sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "11min"],
                     ["--timeout", "11min is out of range", "1ms .. 10min"], "sdo --timeout too long")
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5", "--duration", "20s"], r"node 5 up"):
            rc, out, err = expect_ok_quiet(hb, ["canopen", "sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout",
                                                "2s"], "sdo read --timeout 2s")
            expect_warning(hb, ["canopen", "sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "2000"],
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

    # stepdir: --pulse / --dir-setup / --dir-hold with units (ns is in the grammar); the old
    # unit-in-the-name options are hidden aliases that warn and give the same plan.
    plan = ["stepdir", "plan", "--distance", "500", "--summary", "--verify"]
    _, new_out, _ = expect_ok_quiet(hb, plan + ["--pulse", "30us", "--dir-setup", "200ns", "--dir-hold", "5us"],
                                    "stepdir plan --pulse 30us --dir-setup 200ns --dir-hold 5us")
    check("verify: ok" in new_out, f"stepdir plan with units verifies: {new_out}")
    expect_warning(hb, plan + ["--pulse-us", "30", "--dir-setup", "200ns", "--dir-hold", "5us"],
                   "--pulse-us is deprecated; write --pulse 30us", "stepdir --pulse-us (old name)")
    expect_warning(hb, plan + ["--pulse", "30us", "--dir-setup-ns", "200", "--dir-hold", "5us"],
                   "--dir-setup-ns is deprecated; write --dir-setup 200ns", "stepdir --dir-setup-ns (old name)")
    expect_warning(hb, plan + ["--pulse", "30us", "--dir-setup", "200ns", "--dir-hold-ns", "5000"],
                   "--dir-hold-ns is deprecated; write --dir-hold 5000ns", "stepdir --dir-hold-ns (old name)")
    rc, old_out, err = run(hb, *plan, "--pulse-us", "30", "--dir-setup-ns", "200", "--dir-hold-ns", "5000")
    check(rc == 0 and old_out == new_out, f"old and new stepdir spellings plan the same move: {old_out} {err}")
    expect_warning(hb, plan + ["--pulse", "30"], "write --pulse 30us", "stepdir --pulse bare number = us")
    expect_warning(hb, plan + ["--dir-setup", "200"], "write --dir-setup 200ns", "stepdir --dir-setup bare = ns")
    expect_usage(hb, plan + ["--pulse", "2.5us"], ["--pulse 2500ns", "whole microseconds"], "stepdir --pulse 2.5us")
    expect_usage(hb, plan + ["--pulse", "40us"], ["IP247 MD error"], "stepdir --pulse beyond the machine data")
    expect_usage(hb, plan + ["--dir-setup", "2s"], ["--dir-setup", "2s is out of range", "0s .. 1s"],
                 "stepdir --dir-setup 2s")
    expect_usage(hb, plan + ["--dir-hold", "5 parsecs"], ["--dir-hold", "not a duration", "ns, us, ms, s or min"],
                 "stepdir --dir-hold with an unknown unit")
    rc, out, _ = run(hb, "stepdir", "plan", "--help")
    check("--pulse" in out and "--dir-setup" in out and "--pulse-us" not in out and "-ns" not in out,
          f"stepdir plan --help: {out}")

    # --help shows the new spellings only
    rc, out, _ = run(hb, "can", "send", "--help")
    check("--interval" in out and "--interval-ms" not in out, f"can send --help: {out}")
    rc, out, _ = run(hb, "latency", "--help")
    check("--duration" in out and "--seconds" not in out, f"latency --help: {out}")


def subcommands(hb, path):
    """The subcommands listed by `hilbridge PATH --help`."""
    rc, out, _ = run(hb, *path, "--help")
    check(rc == 0, f"{' '.join(path)} --help: exit {rc}")
    if "Subcommands:" not in out:
        return []
    return re.findall(r"^  ([a-z0-9][a-z0-9-]*)\s{2,}", out.split("Subcommands:", 1)[1], re.M)


def leaf_commands(hb, path=()):
    subs = subcommands(hb, list(path))
    if not subs:
        return [list(path)]
    leaves = []
    for s in subs:
        leaves += leaf_commands(hb, path + (s,))
    return leaves


def check_exit_codes(hb):
    leaves = leaf_commands(hb)
    names = {" ".join(p) for p in leaves}
    # The tree is found, not listed: a new command is covered without touching this test.
    for must in ("canopen sdo read", "modbus write", "can dump", "emulate clm14", "profile calc ip247", "upload",
                 "download", "run", "test", "latency", "stepdir plan", "canopen eds check", "canopen nmt",
                 "canopen scan"):
        check(must in names, f"{must!r} found in the --help tree: {sorted(names)}")
    for path in leaves:
        rc, out, err = run(hb, *path, "--no-such-option")
        check(rc == 2, f"{' '.join(path)} --no-such-option: exit {rc}, expected 2: {err.strip()[:200]}")
        check("Run with --help" in err, f"{' '.join(path)}: a usage message on stderr: {err.strip()[:200]}")
    # A group without its subcommand is a usage error too.
    for group in ("emulate", "can", "canopen", "canopen sdo", "canopen eds", "sdo", "modbus", "profile", "stepdir",
                  "eds"):
        rc, _, err = run(hb, *group.split())
        check(rc == 2, f"{group} without a subcommand: exit {rc}, expected 2: {err.strip()[:200]}")

    # Wrong values, found by the command itself (after CLI11): 2, and nothing is sent.
    usage = [
        ["modbus", "read", "127.0.0.1:1502", "1", "0", "--type", "f32"],
        ["modbus", "write", "127.0.0.1:1502", "1", "0", "70000"],
        ["modbus", "write", "127.0.0.1:1502", "1", "0", "1", "2", "--fc", "6"],
        ["modbus", "read", "127.0.0.1:99999", "1", "0"],
        ["can", "send", "--bus", "nota://bus", "701#05"],
        ["can", "send", "--bus", "vcan0", "701#XYZ"],
        ["can", "dump", "--bus", "nota://bus"],
        ["can", "hub", "--listen", "nonsense"],
        ["canopen", "sdo", "read", "--bus", "vcan0", "5", "not-an-object"],
        ["canopen", "sdo", "write", "--bus", "vcan0", "5", "0x6060:0", "1", "--type", "no-such-type"],
        ["canopen", "nmt", "start", "999", "--bus", "vcan0"],
        ["run", "no/such/scenario.yaml"],
        ["profile", "show", "no-such-device"],
        ["profile", "calc", "ip247"],
        ["canopen", "eds", "check", "no/such/file.eds"],
        ["emulate", "cia402", "--bus", "vcan0", "--node", "5", "--node", "5"],
        ["emulate", "modbus-drive", "--listen", "nonsense"],
        ["emulate", "modbus-drive", "--profile", "no_such_profile"],
        ["emulate", "clm14", "--tcp", "70000"],
        ["download", "clm14", "--port", "/dev/null", "no/such/file.prg", "--yes"],
        ["upload", "clm14", "--port", "/dev/null"],
        ["latency", "--period", "10us"],
        ["stepdir", "verify", "no/such/edges.log"],
    ]
    for args in usage:
        rc, _, err = run(hb, *args)
        check(rc == 2, f"{' '.join(args)}: exit {rc}, expected 2: {err.strip()[:300]}")

    # The checked thing failed: 1.
    failed = [
        ["modbus", "read", "127.0.0.1:1", "1", "0", "--timeout", "200ms"],
        ["can", "send", "--bus", "socketcand://127.0.0.1:1/can0", "701#05"],
        ["can", "dump", "--bus", "socketcand://127.0.0.1:1/can0", "--duration", "1s"],
        ["canopen", "scan", "--bus", "socketcand://127.0.0.1:1/can0"],
        ["canopen", "sdo", "read", "--bus", "socketcand://127.0.0.1:1/can0", "5", "0x1000:0"],
        ["canopen", "nmt", "start", "5", "--bus", "socketcand://127.0.0.1:1/can0"],
        ["test", "tests/runtime/data/wrong_expectation.yaml"],
    ]
    for args in failed:
        rc, _, err = run(hb, *args)
        check(rc == 1, f"{' '.join(args)}: exit {rc}, expected 1: {err.strip()[:300]}")
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        rc, _, err = run(hb, "canopen", "sdo", "read", "--bus", bus, "5", "0x1000:0", "--timeout", "100ms")
        check(rc == 1, f"sdo read of a node that does not answer: exit {rc}, expected 1: {err}")
        rc, _, err = run(hb, "can", "send", "--bus", bus, "701#05")
        check(rc == 0, f"can send to a hub: exit {rc}, expected 0: {err}")
        rc, _, err = run(hb, "canopen", "scan", "--bus", bus, "--timeout", "100ms")
        check(rc == 0, f"scan of an empty bus: exit {rc}, expected 0: {err}")
    rc, _, err = run(hb, "test", "examples/tests/point_to_point.yaml")
    check(rc == 0, f"test of a passing scenario: exit {rc}: {err}")


def check_types(hb):
    # One set of type names: sdo's u8/u16/u32, i8/i16/i32, x16/x32 (hex); modbus the same, s16/s32 warn.
    sys.path.insert(0, __file__.rsplit("/", 2)[0] + "/modbus")
    from emulator import Emulator  # noqa: E402  (tests/modbus/emulator.py)
    with Emulator(hb) as emu:
        ep = f"127.0.0.1:{emu.port}"
        expect_ok_quiet(hb, ["modbus", "write", ep, "1", "2", "-123456", "--type", "i32"], "modbus write --type i32")
        rc, out, _ = expect_ok_quiet(hb, ["modbus", "read", ep, "1", "2", "--type", "i32"], "modbus read --type i32")
        check(out.strip() == "2: -123456", f"i32 read back: {out}")
        rc, out, _ = expect_warning(hb, ["modbus", "read", ep, "1", "2", "--type", "s32"],
                                    "--type s32 is deprecated; write --type i32", "modbus --type s32 (old name)")
        check(out.strip() == "2: -123456", f"s32 still reads the same: {out}")
        expect_warning(hb, ["modbus", "read", ep, "1", "2", "--type", "s16"], "write --type i16",
                       "modbus --type s16 (old name)")
        rc, out, _ = expect_ok_quiet(hb, ["modbus", "read", ep, "1", "10", "--type", "x16"], "modbus --type x16")
        check(re.fullmatch(r"10: 0x[0-9A-F]{4}", out.strip()) is not None, f"x16 = hex: {out}")
    rc, out, _ = run(hb, "modbus", "read", "--help")
    check("i16" in out and "i32" in out and "s16" not in out, f"modbus --help names i16/i32: {out}")
    rc, out, _ = run(hb, "canopen", "sdo", "read", "--help")
    check(all(t in out for t in ("u8", "u16", "u32", "i8", "i16", "i32", "x16", "x32")), f"sdo --help types: {out}")
    expect_usage(hb, ["modbus", "read", "127.0.0.1:1502", "1", "0", "--type", "f32"],
                 ["--type 'f32'", "u16, i16, u32, i32 or hex"], "modbus --type f32")

    # sdo: hex as in modbus and the profiles, its width the object's (read: the size uploaded;
    # write: the digits given), the same value as the x type of that width.
    check("hex" in out, f"sdo --help names hex: {out}")
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5", "--duration", "30s"], r"node 5 up"):
            sdo = ["canopen", "sdo", "read", "--bus", bus, "5"]
            _, out, _ = expect_ok_quiet(hb, sdo + ["0x1018:1", "--type", "hex"], "sdo read --type hex")
            check(out.strip() == "0x00000A11", f"sdo hex of a u32 = x32: {out}")
            _, x32, _ = run(hb, *sdo, "0x1018:1", "--type", "x32")
            check(out == x32, f"sdo hex = x32 for a 32-bit object: {out} {x32}")
            _, out, _ = expect_ok_quiet(hb, sdo + ["0x6060:0", "--type", "hex"], "sdo read --type hex of an i8")
            check(re.fullmatch(r"0x[0-9A-F]{2}", out.strip()) is not None, f"sdo hex of an 8-bit object: {out}")
            _, out, _ = expect_ok_quiet(hb, sdo + ["0x1018:1", "--type", "hex", "--json"], "sdo read --type hex --json")
            j = json.loads(out)
            check(j.get("value") == "0x00000A11" and j.get("type") == "hex", f"sdo hex --json: {out}")
            expect_ok_quiet(hb, ["canopen", "sdo", "write", "--bus", bus, "5", "0x607A:0", "0x0001E240", "--type", "hex"],
                            "sdo write --type hex (32 bits from 8 digits)")
            _, out, _ = run(hb, *sdo, "0x607A:0", "--type", "i32")
            check(out.strip() == "123456", f"hex write read back as i32: {out}")
            expect_usage(hb, ["canopen", "sdo", "write", "--bus", bus, "5", "0x607A:0", "0x1E240", "--type", "hex"],
                         ["0x1E240", "takes its width from the digits", "x8..x64"], "sdo write --type hex, 5 digits")


def check_endpoints(hb):
    # TCP endpoints: HOST:PORT or tcp://HOST:PORT everywhere; serial devices --port; CAN --bus URL.
    with Proc([hb, "can", "hub", "--listen", "tcp://127.0.0.1:0"], r"socketcand://127\.0\.0\.1:(\d+)/can0") as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        expect_ok_quiet(hb, ["can", "send", "--bus", bus, "701#05"], "can send to a hub on tcp://")
    with Proc([hb, "emulate", "modbus-drive", "--listen", "tcp://127.0.0.1:0"], r"listening on 127\.0\.0\.1:(\d+)") as m:
        port = m.m.group(1)
        for ep in (f"127.0.0.1:{port}", f"tcp://127.0.0.1:{port}"):
            rc, out, err = expect_ok_quiet(hb, ["modbus", "read", ep, "1", "10", "--type", "hex"], f"modbus read {ep}")
            check(out.startswith("10: 0x"), f"modbus read {ep}: {out}")
    expect_usage(hb, ["modbus", "read", "tcp://127.0.0.1:99999", "1", "0"], ["99999", "1..65535"],
                 "modbus tcp:// with a bad port")
    emu = subprocess.Popen([hb, "emulate", "clm14", "--tcp", "0", "--state", "none", "--mode", "parameter"],
                           stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        addr = emu.stdout.readline().strip()  # tcp:127.0.0.1:PORT, as before
        check(addr.startswith("tcp:127.0.0.1:"), f"emulate clm14 --tcp prints its address: {addr}")
        port = addr.rsplit(":", 1)[1]
        with tempfile.TemporaryDirectory() as d:
            for i, spelling in enumerate((f"tcp://127.0.0.1:{port}", addr)):
                out = os.path.join(d, f"p{i}.prg")
                rc, _, err = expect_ok_quiet(hb, ["upload", "clm14", "--port", spelling, "--what", "program",
                                                  "--out", out], f"upload --port {spelling}")
                check(os.path.exists(out), f"upload --port {spelling} wrote {out}")
    finally:
        emu.stdin.write("quit\n")
        emu.stdin.flush()
        emu.wait(timeout=10)


def check_groups(hb):
    # One grouping rule (docs/cli.md, "Command groups"): a command that speaks one protocol lives in
    # its group; the CANopen services and EDS tools are `canopen sdo|nmt|scan|eds`. The old top-level
    # names are hidden aliases that work as before and warn once, naming the new spelling.
    top = subcommands(hb, [])
    check("canopen" in top and not {"sdo", "nmt", "scan", "eds"} & set(top), f"hilbridge --help groups: {top}")
    check(set(subcommands(hb, ["canopen"])) == {"sdo", "nmt", "scan", "eds"}, "canopen sdo|nmt|scan|eds")
    for group, protocol_commands in (("can", {"dump", "send"}), ("modbus", {"read", "write"}),
                                     ("stepdir", {"plan", "verify"})):
        subs = set(subcommands(hb, [group]))
        check(protocol_commands <= subs, f"{group} groups its protocol's commands: {subs}")
    eds = "profiles/canopen/hil_cia402_drive.eds"
    _, new_out, _ = expect_ok_quiet(hb, ["canopen", "eds", "check", eds], "canopen eds check")
    _, old_out, _ = expect_warning(hb, ["eds", "check", eds], "hilbridge eds is deprecated; write hilbridge canopen eds",
                                   "eds check (old top-level name)")
    check(old_out == new_out and new_out, f"eds check: the old name does the same: {old_out!r}")
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5", "--duration", "30s"], r"node 5 up"):
            read = ["sdo", "read", "--bus", bus, "5", "0x1018:1", "--type", "x32"]
            _, new_out, _ = expect_ok_quiet(hb, ["canopen", *read], "canopen sdo read")
            _, old_out, _ = expect_warning(hb, read, "hilbridge sdo is deprecated; write hilbridge canopen sdo",
                                           "sdo read (old top-level name)")
            check(old_out == new_out == "0x00000A11\n", f"sdo read: the old name does the same: {old_out!r}")
            expect_warning(hb, ["sdo", "write", "--bus", bus, "5", "0x607A:0", "7", "--type", "i32"],
                           "write hilbridge canopen sdo", "sdo write (old top-level name)")
            _, new_out, _ = expect_ok_quiet(hb, ["canopen", "scan", "--bus", bus, "--timeout", "200ms"], "canopen scan")
            _, old_out, _ = expect_warning(hb, ["scan", "--bus", bus, "--timeout", "200ms"],
                                           "hilbridge scan is deprecated; write hilbridge canopen scan",
                                           "scan (old top-level name)")
            check(old_out == new_out and "0x00000A11" in new_out, f"scan: the old name does the same: {old_out!r}")
            expect_ok_quiet(hb, ["canopen", "nmt", "preop", "--bus", bus, "5"], "canopen nmt")
            expect_warning(hb, ["nmt", "start", "--bus", bus, "5"],
                           "hilbridge nmt is deprecated; write hilbridge canopen nmt", "nmt (old top-level name)")
    # Usage errors stay usage errors under either name.
    for args in (["sdo", "read", "--bus", "vcan0", "5", "not-an-object"], ["nmt", "start", "999", "--bus", "vcan0"]):
        rc, _, err = run(hb, *args)
        check(rc == 2 and "deprecated" in err, f"{' '.join(args)}: exit {rc}, expected 2 and the warning: {err}")


def main():
    hb, part = sys.argv[1], sys.argv[2]
    {"durations": check_durations, "exit_codes": check_exit_codes, "types": check_types,
     "endpoints": check_endpoints, "groups": check_groups}[part](hb)
    print(f"{c_passed} passed, {c_failed} failed")
    sys.exit(1 if c_failed or not c_passed else 0)


if __name__ == "__main__":
    main()
