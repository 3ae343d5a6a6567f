# SPDX-License-Identifier: MIT
"""A limit-switch run per device ends with the device's own error number where users read it:
the `hilbridge run` summary, `run --json` (controller.device_errors) and the JUnit report of
`hilbridge test` (issue 14). The shipped examples are the runs; each expects its device fault, so
`hilbridge test` passes and the error shows in the run case's <system-out>.
Usage: /usr/bin/python3 limit_switch_cli.py HILBRIDGE   (from the source tree's root)"""
import json
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

RUNS = [  # (scenario, category, code, text in the device's catalogue)
    ("examples/controllers/wf725-726-limit-switch.yaml", "wf725-726.traversing", "16", "Range limit switch positive"),
    ("examples/controllers/ip247.yaml", "ip247.module", "26", 'HW limit "end" overrun'),
    ("examples/controllers/clm14-limit-switch.yaml", "clm14.diagnostic", "47", "Max Travel Lmt 1"),
]

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


hb = sys.argv[1]
for scenario, category, code, text in RUNS:
    full = f"{category}:{code}"
    p = subprocess.run([hb, "run", "--virtual", "-q", scenario], capture_output=True, text=True, timeout=120)
    summary = [line for line in p.stdout.splitlines() if "device error" in line]
    check(len(summary) == 1 and full in summary[0] and text in summary[0],
          f"{scenario}: summary line 'device error ... {full} {text}': {summary or p.stdout[-600:]}")

    p = subprocess.run([hb, "run", "--virtual", "--json", scenario], capture_output=True, text=True, timeout=120)
    try:
        errors = json.loads(p.stdout)["controller"]["device_errors"]
    except (ValueError, KeyError, TypeError) as e:
        errors = []
        check(False, f"{scenario}: run --json has no controller.device_errors ({e}): {p.stdout[:300]}")
    check(len(errors) == 1 and errors[0].get("category") == category and errors[0].get("code") == code
          and text in errors[0].get("text", ""), f"{scenario}: run --json device_errors: {errors}")

    with tempfile.NamedTemporaryFile(suffix=".xml") as junit:
        p = subprocess.run([hb, "test", scenario, "--junit", junit.name], capture_output=True, text=True, timeout=120)
        check(p.returncode == 0, f"{scenario}: hilbridge test exit {p.returncode}: {p.stdout[-400:]}")
        root = ET.parse(junit.name).getroot()
        outs = [e.text or "" for e in root.iter("system-out")]
        check(any(full in o and text in o for o in outs),
              f"{scenario}: JUnit <system-out> without '{full} {text}': {[o[:200] for o in outs]}")
        names = [tc.get("name", "") for tc in root.iter("testcase")]
        check(any(full in n for n in names), f"{scenario}: no JUnit case for the expected fault {full}: {names}")

for f in failures:
    print("FAIL:", f)
print(f"limit-switch runs: {len(RUNS)} devices, {len(failures)} failures")
sys.exit(1 if failures else 0)
