# SPDX-License-Identifier: MIT
"""`--json` / `--jsonl` output of the hilbridge commands as a program reads it (docs/json.md): the
real binary against targets that need no hardware (the shipped scenarios and profiles, a Modbus
emulator, a CiA 402 node behind our socketcand hub). Every document goes through
`python3 -m json.tool`, then a few members are checked; errors under --json are an object with
"error" on stdout, the message on stderr and the usual exit status.
Usage: /usr/bin/python3 json_cli.py HILBRIDGE test|run|scan|sdo_read|modbus_read|profile|can_dump
(run from the source tree's root)."""
import json
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, __file__.rsplit("/", 2)[0] + "/modbus")
from emulator import Checks, Emulator  # noqa: E402  (tests/modbus/emulator.py)

c = Checks()


def run(hb, *args, timeout=60):
    p = subprocess.run([hb, *args], capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def json_tool(text, what):
    """Validates with `python3 -m json.tool` (the tool CI users run); returns the parsed value."""
    p = subprocess.run([sys.executable, "-m", "json.tool"], input=text, capture_output=True, text=True, timeout=20)
    c.check(p.returncode == 0, f"{what}: json.tool rejects stdout: {p.stderr.strip()} in {text[:400]!r}")
    try:
        return json.loads(text)
    except ValueError:
        return {}


def expect_error(hb, args, rc_wanted, what):
    rc, out, err = run(hb, *args)
    c.check(rc == rc_wanted, f"{what}: exit {rc}, expected {rc_wanted}: {err}")
    j = json_tool(out, what)
    c.check(isinstance(j, dict) and isinstance(j.get("error"), str) and j["error"], f"{what}: no error member: {out}")
    c.check(isinstance(j, dict) and j.get("exit_code") == rc_wanted, f"{what}: exit_code member: {out}")
    c.check(err.strip() != "", f"{what}: the message on stderr too")
    return j


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
        self.p.communicate(timeout=10)


def hub(hb):
    return Proc([hb, "can", "hub", "--listen", "127.0.0.1:0"], r"socketcand://127\.0\.0\.1:(\d+)/can0")


def check_test(hb):
    # Scenarios on simulated drives only: deterministic however loaded the machine is.
    rc, out, err = run(hb, "test", "examples/tests/point_to_point.yaml", "examples/tests/rotary_shortest_path.yaml",
                       "--json", timeout=120)
    c.check(rc == 0, f"test --json: exit {rc}: {err}")
    j = json_tool(out, "test --json")
    c.check(j.get("ok") is True and j.get("failed") == 0 and j.get("total") == len(j.get("scenarios", [])) > 0,
            f"test summary: {out[:300]}")
    s = j.get("scenarios", [{}])[0]
    c.check({"file", "scenario", "ok", "simulated_s", "failures", "expectations", "cut_off"} <= s.keys(), f"keys {s}")
    c.check("PASS" in err, "the PASS/FAIL lines go to stderr under --json")
    with tempfile.NamedTemporaryFile("w", suffix=".yaml") as f:
        f.write(open("tests/runtime/data/wrong_expectation.yaml").read())
        f.flush()
        rc, out, _ = run(hb, "test", f.name, "--json")
        j = json_tool(out, "test --json failing")
        c.check(rc == 1 and j.get("ok") is False and j.get("failed") == 1, f"failing scenario: {rc} {out[:300]}")
        e = [x for x in j["scenarios"][0]["expectations"] if not x["passed"]]
        c.check(e and e[0]["detail"] and e[0]["line"] > 0, f"failed expectation with detail and line: {e}")
    expect_error(hb, ["test", "no/such/folder", "--json"], 2, "test --json missing path")


def check_run(hb):
    rc, out, err = run(hb, "run", "--virtual", "examples/demo.yaml", "--json")
    c.check(rc == 0, f"run --json: exit {rc}: {err}")
    j = json_tool(out, "run --json")
    c.check(j.get("ok") is True and j.get("cut_off") is None and len(j.get("axes", [])) == 3, f"run: {out[:300]}")
    rc, out, _ = run(hb, "run", "--virtual", "examples/demo.yaml", "--json", "--duration", "1s")
    j = json_tool(out, "run --json --duration")
    cut = j.get("cut_off") or {}
    c.check(cut.get("expected") is True and "cut off by duration at t=1.000 s" in cut.get("reason", ""),
            f"--duration cuts as asked: {cut}")
    # The demo's end-of-run expectations fail after 1 s, the cut itself does not.
    c.check(rc == 1 and j["failures"] and not any("cut off" in f for f in j["failures"]), f"failures: {j['failures']}")
    expect_error(hb, ["run", "--virtual", "examples/demo.yaml", "--json", "--duration", "fast"], 2, "run bad option")


def check_scan(hb):
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5", "--node", "9"], r"node \d+ up"):
            rc, out, err = run(hb, "canopen", "scan", "--bus", bus, "--timeout", "200ms", "--json")
            c.check(rc == 0, f"scan --json: exit {rc}: {err}")
            j = json_tool(out, "scan --json")
            nodes = {n["node"]: n for n in j.get("nodes", [])}
            c.check(j.get("count") == 2 and set(nodes) == {5, 9}, f"scan nodes: {out}")
            n5 = nodes.get(5, {})
            c.check(n5.get("device_type") == 0x20192 and n5.get("vendor_id") == 0xA11 and
                    n5.get("product_code") == 0x402 and "CiA 402" in n5.get("name", ""), f"node 5 identity: {n5}")
    expect_error(hb, ["canopen", "scan", "--bus", "socketcand://127.0.0.1:1/can0", "--json"], 1, "scan unreachable bus")


def check_sdo_read(hb):
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        with Proc([hb, "emulate", "cia402", "--bus", bus, "--node", "5"], r"node 5 up"):
            rc, out, err = run(hb, "canopen", "sdo", "read", "--bus", bus, "5", "0x1018:1", "--type", "u32", "--json")
            j = json_tool(out, "sdo read --json")
            c.check(rc == 0 and j.get("value") == 0xA11 and j.get("data") == "110a0000" and j.get("size") == 4 and
                    j.get("index") == "0x1018" and j.get("subindex") == 1, f"sdo read u32: {rc} {out} {err}")
            rc, out, _ = run(hb, "canopen", "sdo", "read", "--bus", bus, "5", "0x1008:0", "--type", "vs", "--json")
            j = json_tool(out, "sdo read vs")
            c.check(rc == 0 and "CiA 402" in str(j.get("value")), f"sdo read vs: {out}")
            rc, out, _ = run(hb, "canopen", "sdo", "read", "--bus", bus, "5", "0x1000:0", "--json")
            j = json_tool(out, "sdo read untyped")
            c.check(rc == 0 and j.get("type") is None and j.get("value") == 0x20192, f"untyped: {out}")
            j = expect_error(hb, ["canopen", "sdo", "read", "--bus", bus, "5", "0x1018:9", "--json"], 1, "sdo abort")
            c.check(j.get("abort_code") == "0x06090011", f"abort code member: {j}")
            expect_error(hb, ["canopen", "sdo", "read", "--bus", bus, "5", "zz:1", "--json"], 2, "sdo bad object")
    expect_error(hb, ["canopen", "sdo", "read", "--bus", "vcan0", "5", "--json"], 2, "sdo usage error")


def check_modbus_read(hb):
    with Emulator(hb, "cia402") as emu:
        ep = f"127.0.0.1:{emu.port}"
        rc, _, err = run(hb, "modbus", "write", ep, "1", "2", "-123456", "--type", "i32")
        c.check(rc == 0, f"modbus write: {err}")
        rc, out, err = run(hb, "modbus", "read", ep, "1", "2", "--type", "i32", "--json")
        j = json_tool(out, "modbus read --json")
        v = j.get("values", [{}])[0]
        c.check(rc == 0 and j.get("function_code") == 3 and v.get("address") == 2 and v.get("value") == -123456 and
                v.get("registers") == [0xFFFE, 0x1DC0], f"modbus read s32: {rc} {out} {err}")
        rc, out, _ = run(hb, "modbus", "read", ep, "1", "10", "3", "--type", "hex", "--json")
        j = json_tool(out, "modbus read hex")
        c.check(rc == 0 and [x["address"] for x in j.get("values", [])] == [10, 11, 12] and
                all(re.fullmatch(r"0x[0-9A-F]{4}", x["hex"]) for x in j["values"]), f"hex: {out}")
        j = expect_error(hb, ["modbus", "read", ep, "1", "0", "1", "--input", "--json"], 1, "modbus exception")
        c.check("exception 02" in j.get("error", ""), f"exception in the error: {j}")
    expect_error(hb, ["modbus", "read", "127.0.0.1:1", "1", "0", "--timeout", "500ms", "--json"], 1, "no server")
    expect_error(hb, ["modbus", "read", "127.0.0.1:1502", "1", "--json"], 2, "modbus usage error")


def check_profile(hb):
    rc, out, _ = run(hb, "profile", "show", "clm14", "--json")
    j = json_tool(out, "profile show")
    c.check(rc == 0 and j.get("device") == "clm14" and len(j.get("parameters", [])) > 10 and j.get("catalogues"),
            f"overview: {out[:300]}")
    rc, out, _ = run(hb, "profile", "show", "clm14", "A106", "--json")
    j = json_tool(out, "profile show PARAM")
    f = j.get("variants", [{}])[0].get("fields", [{}])[0]
    c.check(rc == 0 and j.get("id") == "A106" and f.get("ranges") and f["ranges"][0].get("max") is not None,
            f"parameter: {out[:400]}")
    rc, out, _ = run(hb, "profile", "show", "ip247", "--errors", "--json")
    j = json_tool(out, "profile show --errors")
    c.check(rc == 0 and sum(len(x["entries"]) for x in j.get("catalogues", [])) > 50, f"catalogues: {out[:200]}")
    rc, out, _ = run(hb, "profile", "show", "ip247", "59", "--json")
    j = json_tool(out, "profile show CODE")
    c.check(rc == 0 and any("Referenznocken" in e["text_de"] for e in j.get("error_codes", [])), f"code: {out[:300]}")
    rc, out, _ = run(hb, "profile", "encode", "wf725-726", "MD11", "--json", "--", "-24537")
    j = json_tool(out, "profile encode")
    w = j.get("wire", {})
    c.check(rc == 0 and w.get("bcd") == "80024537" and w.get("binary") == "FFFFA027" and j.get("problems") == [],
            f"encode: {out}")
    rc, out, _ = run(hb, "profile", "encode", "clm14", "A106", "60000", "--json")
    j = json_tool(out, "profile encode out of range")
    c.check(rc == 1 and any("0.1..50000" in p["rule"] for p in j.get("problems", [])), f"range problem: {rc} {out}")
    rc, out, _ = run(hb, "profile", "decode", "wf725-726", "MD11", "HEX FFFF A027", "--json")
    j = json_tool(out, "profile decode")
    c.check(rc == 0 and j.get("value") == "-24537", f"decode: {out}")
    expect_error(hb, ["profile", "decode", "wf725-726", "MD11", "8002 45A7", "--json"], 1, "decode bad digit")
    rc, out, _ = run(hb, "profile", "validate", "wf725-726", "tests/profiles/data/wf725_valid.txt", "--json")
    j = json_tool(out, "profile validate valid")
    c.check(rc == 0 and j.get("valid") is True and j.get("parameters", 0) > 0, f"valid set: {rc} {out[:300]}")
    rc, out, _ = run(hb, "profile", "validate", "wf725-726", "tests/profiles/data/wf725_errors.txt", "--json")
    j = json_tool(out, "profile validate errors")
    c.check(rc == 1 and j.get("valid") is False and any(p["line"] for p in j.get("problems", [])),
            f"problems with lines: {rc} {out[:300]}")
    expect_error(hb, ["profile", "show", "no-such-device", "--json"], 2, "unknown device")
    expect_error(hb, ["profile", "validate", "clm14", "no/such/file.par", "--json"], 2, "missing set")


def check_can_dump(hb):
    with hub(hb) as h:
        bus = f"socketcand://127.0.0.1:{h.m.group(1)}/can0"
        dump = subprocess.Popen([hb, "can", "dump", "--bus", bus, "--jsonl", "--count", "3", "--duration", "20s"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        # the dump says on stderr when it listens; send only then
        line = dump.stderr.readline()
        c.check("listening on" in line, f"dump started: {line!r}")
        rc, _, err = run(hb, "can", "send", "--bus", bus, "705#05", "12345678#DEADBEEF", "000#0105")
        c.check(rc == 0, f"can send: {err}")
        out, err = dump.communicate(timeout=30)
        c.check(dump.returncode == 0, f"dump exit {dump.returncode}: {err}")
        lines = out.splitlines()
        c.check(len(lines) == 3, f"one line per frame: {out!r}")
        frames = [json_tool(ln, f"jsonl line {i}") for i, ln in enumerate(lines)]
        if len(frames) == 3:
            c.check(frames[0]["id"] == 0x705 and frames[0]["data"] == "05" and frames[0]["dlc"] == 1 and
                    not frames[0]["extended"] and frames[0]["bus"] == "can0", f"heartbeat: {frames[0]}")
            c.check(frames[1]["extended"] and frames[1]["id_hex"] == "12345678" and frames[1]["data"] == "deadbeef",
                    f"extended: {frames[1]}")
            c.check(frames[0]["time_us"] <= frames[1]["time_us"] <= frames[2]["time_us"] and frames[0]["time"] > 1e9,
                    f"wall-clock times in order: {[f['time_us'] for f in frames]}")
    expect_error(hb, ["can", "dump", "--bus", "nonsense://x", "--jsonl"], 2, "dump bad bus")


def main():
    hb, what = sys.argv[1], sys.argv[2]
    globals()["check_" + what](hb)
    c.exit()


if __name__ == "__main__":
    main()
