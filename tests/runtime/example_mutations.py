#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The controller example scenarios fail when the behaviour they check is wrong.

Each expectation of every examples/controllers/*.yaml is mutated once (a value +7, moves and
edges +1, a position +10, a state flipped, an edge window moved past its end, a device error code
+1, an axis fault code or bit +1) and the mutated scenario must FAIL under `hilbridge test` on that
very expectation (not on a load error or another expectation); the unmutated ones must pass.
Usage: example_mutations.py HILBRIDGE [GLOB]   (run from the source root; GLOB defaults to
examples/controllers/*.yaml)
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def mutate(line, taken=()):
    """The mutated line, or None. `taken`: the fault codes the scenario expects elsewhere (a fault
    mutated into one of them would still be raised: no mutant)."""
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
        # the window [after, by] moved to just past its end: an edge inside the old window is
        # now too early
        def seconds(key):
            m = re.search(key + r": ([0-9.]+)(ms|s)\b", line)
            return None if not m else float(m.group(1)) / (1000.0 if m.group(2) == "ms" else 1.0)
        by = seconds("by")
        if by is not None:
            window = "after: %.6fs, by: %.6fs" % (by + 0.001, by + 0.002)
            if seconds("after") is not None:
                return re.sub(r"after: [0-9.]+(ms|s), by: [0-9.]+(ms|s)", window, line)
            return re.sub(r"by: [0-9.]+(ms|s)", window, line)
    if "fault: " in line:
        def fault(m):
            prefix, code = m.group(1), m.group(2)
            bit = code.startswith("bit")
            n = int(code[3:] if bit else code) + 1
            while "%s:%s%d" % (prefix[len('fault: "'):], "bit" if bit else "", n) in taken:
                n += 1
            return '%s:%s%d"' % (prefix, "bit" if bit else "", n)
        return re.sub(r'(fault: "[^":]+):(bit\d+|\d+)"', fault, line)
    if "clm14.diagnostic:" in line:
        return re.sub(r"diagnostic:([0-9A-F]+)", lambda m: "diagnostic:%02X" % (int(m.group(1), 16) + 1), line)
    return None


def run(hilbridge, paths):
    """One `hilbridge test --json` over every path: {file: scenario summary}."""
    r = subprocess.run([hilbridge, "test", "--json"] + paths, capture_output=True, text=True)
    try:
        summary = json.loads(r.stdout)
    except ValueError:
        print("hilbridge test printed no JSON summary (exit %d):\n%s" % (r.returncode, r.stderr[-2000:]))
        return None
    return {s["file"]: s for s in summary.get("scenarios", [])}


def main():
    hilbridge = sys.argv[1]
    files = sorted(glob.glob(sys.argv[2] if len(sys.argv) > 2 else "examples/controllers/*.yaml"))
    if not files:
        print("no scenarios found (run from the source root)")
        return 1
    results = run(hilbridge, files)
    if results is None:
        return 1
    for f in files:
        if f not in results or not results[f]["ok"]:
            print("the unmutated scenario fails: %s" % f)
            return 1
    # Every mutant beside its original in a copy of the tree the scenarios are in (not under
    # examples/, which `hilbridge test examples/` may be reading at the same time), so the parameter
    # and program files it names, also in sibling folders, are where it expects them; and all of
    # them in one `hilbridge test` process: a process per mutant cost most of the time.
    mutants = {}
    root = os.path.relpath(files[0]).split(os.sep)[0]
    with tempfile.TemporaryDirectory() as d:
        shutil.copytree(root, os.path.join(d, root))
        for f in files:
            lines = open(f).read().split("\n")
            if "expect:" not in lines:
                continue
            first = lines.index("expect:") + 1
            taken = set(re.findall(r'fault: "([^"]+)"', "\n".join(lines[first:])))
            for i in range(first, len(lines)):
                m = mutate(lines[i], taken)
                if m is None or m == lines[i]:
                    continue
                changed = list(lines)
                changed[i] = m
                tmp = os.path.join(d, os.path.dirname(os.path.relpath(f)),
                                   "mutant-%04d-%s" % (len(mutants), os.path.basename(f)))
                with open(tmp, "w") as out:
                    out.write("\n".join(changed))
                mutants[tmp] = (f, i + 1, m.strip())
        results = run(hilbridge, sorted(mutants)) if mutants else {}
    if results is None:
        return 1
    survived = []
    for tmp, (f, line, m) in sorted(mutants.items()):
        result = results.get(tmp)
        # detected: the scenario fails, and the mutated expectation itself is among its failures
        # (a mutant that fails only for another reason would not show that this expectation checks)
        detected = result is not None and not result["ok"] and any(
            e["line"] == line and not e["passed"] for e in result.get("expectations", []))
        if not detected:
            survived.append("%s:%d: %s" % (f, line, m))
    print("%d scenarios, %d mutated expectations, %d not detected" % (len(files), len(mutants), len(survived)))
    for s in survived:
        print("  not detected: " + s)
    return 0 if mutants and not survived else 1


if __name__ == "__main__":
    sys.exit(main())
