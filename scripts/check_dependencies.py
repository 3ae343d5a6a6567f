#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks the dependency rules of docs/ARCHITECTURE.md against the code's #include lines.

The table under "## Dependency rules" in docs/ARCHITECTURE.md is the rule: for each area (a folder,
`folder/sub` for the files of a platform subfolder such as protocols/can/linux or src/io/ +
include/hil/<name>/io/, or a single file), which other areas' public headers it may include and
which libraries it may use; a fourth column lists known exceptions still to be removed. Every `#include` of every C++ file under bridge/, protocols/, drives/, profiles/ and mocks/
is mapped to the area that owns the header (by its include root) or to a library (yaml-cpp, asio,
threads, ...); an include that the table does not allow is a violation. Tests, fuzz targets and
benchmarks are not areas. Exit status: 0 all rules hold, 1 violations (each printed as
file:line: what), 2 the table cannot be read.

Usage: check_dependencies.py [--root DIR]   (default: the repository this script is in)
"""
import argparse
import os
import re
import sys

CHECKED_TOPS = ("bridge", "protocols", "drives", "profiles", "mocks")
SOURCE_EXT = (".cpp", ".hpp", ".h", ".cc")

# Library names used in the table's third column, by the include that brings them in.
LIBRARIES = [
    (re.compile(r"^yaml-cpp/"), "yaml-cpp"),
    (re.compile(r"^fmt/"), "fmt"),
    (re.compile(r"^asio(\.hpp|/)"), "asio"),
    (re.compile(r"^modbus(\.h|/)"), "libmodbus"),
    (re.compile(r"^gpiod\.(h|hpp)$"), "libgpiod"),
    (re.compile(r"^CLI/"), "CLI11"),
    (re.compile(r"^nlohmann/"), "nlohmann-json"),
    (re.compile(r"^spdlog/"), "spdlog"),
    (re.compile(r"^(thread|mutex|shared_mutex|condition_variable|future|stop_token|semaphore|latch|barrier)$"), "threads"),
    (re.compile(r"^(sys/|linux/|net/|netinet/|arpa/|asm/|termios\.h$|fcntl\.h$|unistd\.h$|poll\.h$|pty\.h$)"), "posix"),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def read_rules(doc):
    """Rows of the table under '## Dependency rules': {area: (areas, libraries)}."""
    rules, in_section = {}, False
    for line in open(doc, encoding="utf-8"):
        if line.startswith("## "):
            in_section = line.strip() == "## Dependency rules"
            continue
        if not in_section or not line.startswith("|") or set(line.strip()) <= set("|-: "):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) < 3 or not cells[0].startswith("`"):
            continue  # the header row
        names = lambda cell: set(re.findall(r"`([^`]+)`", cell))
        area = cells[0].strip("`")
        # The fourth column lists what an area still does against the rule, to be removed: allowed
        # until then, and printed on every run so it stays visible.
        pending = names(cells[3]) if len(cells) > 3 else set()
        rules[area] = (names(cells[1]) | pending, names(cells[2]) | pending, pending)
    return rules


def area_of(path, areas):
    """The most specific area owning `path` (relative, '/'-separated), or None."""
    best = None
    for a in areas:
        parent, _, last = a.rpartition("/")
        owned = path == a or path.startswith(a + "/") or (
            parent and re.match(rf"^{re.escape(parent)}/(src|include/hil/[^/]+)/{re.escape(last)}/", path))
        if owned and (best is None or len(a) > len(best)):
            best = a
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args = ap.parse_args()
    root = args.root
    doc = os.path.join(root, "docs", "ARCHITECTURE.md")
    rules = read_rules(doc)
    if not rules:
        print(f"{doc}: no '## Dependency rules' table found", file=sys.stderr)
        return 2

    files = []
    for top in CHECKED_TOPS:
        for d, subdirs, names in os.walk(os.path.join(root, top)):
            subdirs[:] = sorted(s for s in subdirs if not s.startswith("build"))
            files += [os.path.relpath(os.path.join(d, n), root).replace(os.sep, "/")
                      for n in sorted(names) if n.endswith(SOURCE_EXT)]
    # Which area owns each public header, by its path below an include root.
    header_owner = {}
    for f in files:
        m = re.match(r"^(.*?)/include/(hil/.*)$", f)
        if m:
            header_owner[m.group(2)] = area_of(f, rules)

    violations, unowned = [], set()
    for f in files:
        a = area_of(f, rules)
        if a is None:
            unowned.add(f.split("/include/")[0].split("/src/")[0])
            continue
        allowed_areas, allowed_libs, _ = rules[a]
        for n, line in enumerate(open(os.path.join(root, f), encoding="utf-8", errors="replace"), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            inc = m.group(2)
            if inc in header_owner:
                b = header_owner[inc]
                if b != a and b is not None and b not in allowed_areas and "*" not in allowed_areas:
                    violations.append(f"{f}:{n}: area {a} includes {inc} of area {b} (allowed: "
                                      f"{', '.join(sorted(allowed_areas)) or 'none'})")
                continue
            for pattern, lib in LIBRARIES:
                if pattern.search(inc) and lib not in allowed_libs and "*" not in allowed_libs:
                    violations.append(f"{f}:{n}: area {a} uses {lib} (<{inc}>) (allowed: "
                                      f"{', '.join(sorted(allowed_libs)) or 'the standard library only'})")
    for a, (_, _, pending) in sorted(rules.items()):
        if pending:
            print(f"pending exception: {a} -> {', '.join(sorted(pending))}")
    for u in sorted(unowned):
        violations.append(f"{u}: no row in the dependency-rules table of docs/ARCHITECTURE.md")
    for v in violations:
        print(v)
    if violations:
        print(f"check_dependencies: {len(violations)} violation(s) of docs/ARCHITECTURE.md § Dependency rules")
        return 1
    print(f"check_dependencies: {len(files)} files in {len(rules)} areas follow docs/ARCHITECTURE.md § Dependency rules")
    return 0


if __name__ == "__main__":
    sys.exit(main())
