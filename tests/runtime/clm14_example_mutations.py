#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The CLM1.4 example scenarios fail when the behaviour they check is wrong.

Each expectation of every examples/controllers/clm14-*.yaml is mutated once (a value +7, moves and
edges +1, a position +10, a state flipped, an edge window moved past its end, a device error code
+1) and the mutated scenario must FAIL under `hilbridge test`; the unmutated ones must pass.
Usage: clm14_example_mutations.py HILBRIDGE [GLOB]   (run from the source root)
"""
import glob
import os
import re
import subprocess
import sys
import tempfile


def mutate(line):
    if "value: " in line:
        def rep(m):
            t = m.group(1)
            v = int(t.replace("_", ""), 0) if t.startswith(("0x", "0b")) else float(t)
            return "value: %s" % (v + 7)
        return re.sub(r"value: ([-+0-9a-fA-Fx_.b]+)", rep, line, count=1)
    if "moves: " in line:
        return re.sub(r"moves: (\d+)", lambda m: "moves: %d" % (int(m.group(1)) + 1), line)
    if "position: " in line:
        return re.sub(r"position: ([-0-9.]+)", lambda m: "position: %s" % (float(m.group(1)) + 10), line)
    if "state: true" in line:
        return line.replace("state: true", "state: false")
    if "state: false" in line:
        return line.replace("state: false", "state: true")
    if "edges: " in line:
        return re.sub(r"edges: (\d+)", lambda m: "edges: %d" % (int(m.group(1)) + 1), line)
    if "first_edge" in line:
        m = re.search(r"by: ([0-9.]+)(ms|s)", line)
        if m:
            later = float(m.group(1)) + (1 if m.group(2) == "ms" else 0.001)
            return re.sub(r"after: [0-9.]+(ms|s)", "after: %s%s" % (later, m.group(2)), line)
    if "clm14.diagnostic:" in line:
        return re.sub(r"diagnostic:([0-9A-F]+)", lambda m: "diagnostic:%02X" % (int(m.group(1), 16) + 1), line)
    return None


def absolute(line, folder):
    m = re.match(r"^(  (?:parameters|program): )(\S+)$", line)
    return m.group(1) + os.path.join(folder, m.group(2)) if m else line


def main():
    hilbridge = sys.argv[1]
    files = sorted(glob.glob(sys.argv[2] if len(sys.argv) > 2 else "examples/controllers/clm14-*.yaml"))
    if not files:
        print("no scenarios found (run from the source root)")
        return 1
    total, survived = 0, []
    for f in files:
        if subprocess.run([hilbridge, "test", f], capture_output=True).returncode != 0:
            print("the unmutated scenario fails: %s" % f)
            return 1
        lines = open(f).read().split("\n")
        if "expect:" not in lines:
            continue
        for i in range(lines.index("expect:") + 1, len(lines)):
            m = mutate(lines[i])
            if m is None or m == lines[i]:
                continue
            total += 1
            changed = [absolute(l, os.path.dirname(os.path.abspath(f))) for l in lines]
            changed[i] = m
            # in a folder of its own (not under examples/, which `hilbridge test examples/` may be
            # reading at the same time), its parameter and program files named by absolute paths
            with tempfile.TemporaryDirectory() as d:
                tmp = os.path.join(d, os.path.basename(f))
                with open(tmp, "w") as out:
                    out.write("\n".join(changed))
                r = subprocess.run([hilbridge, "test", tmp], capture_output=True, text=True)
            if r.returncode == 0:
                survived.append("%s:%d: %s" % (f, i + 1, m.strip()))
    print("%d scenarios, %d mutated expectations, %d not detected" % (len(files), total, len(survived)))
    for s in survived:
        print("  not detected: " + s)
    return 0 if total > 0 and not survived else 1


if __name__ == "__main__":
    sys.exit(main())
