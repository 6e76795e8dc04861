#!/usr/bin/env python3
"""The figures of the house: source files and functions by length, test code
left out, and the arrows between the workspace's crates.

    python3 scripts/sizes.py [--files N] [--functions N] [--list]

A file's length counts its lines outside `#[cfg(test)]` modules; a
function's, from its `fn` line to its closing brace (bodies of functions
inside `#[cfg(test)]` modules and under `tests/`, `benches/` and `fuzz/` are
not counted). Prints the counts over each threshold, and with `--list` every
file and function over it.
"""

import argparse
import json
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FN = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)")


def strip_strings(line: str) -> str:
    """The line with string and char literals and `//` comments blanked, so
    that braces inside them are not counted."""
    out = []
    i, n = 0, len(line)
    while i < n:
        c = line[i]
        if c == "/" and i + 1 < n and line[i + 1] == "/":
            break
        if c == '"':
            i += 1
            while i < n and line[i] != '"':
                i += 2 if line[i] == "\\" else 1
            i += 1
            continue
        if c == "'" and i + 2 < n and (line[i + 2] == "'" or line[i + 1] == "\\"):
            j = line.find("'", i + 2)
            i = j + 1 if j > 0 else i + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def block_end(lines, start):
    """The index of the line closing the block opened at or after `start`."""
    depth, opened = 0, False
    for k in range(start, len(lines)):
        s = strip_strings(lines[k])
        depth += s.count("{") - s.count("}")
        opened = opened or "{" in s
        if opened and depth <= 0:
            return k
        if not opened and s.rstrip().endswith(";"):
            return k
    return len(lines) - 1


def measure(path: Path):
    lines = path.read_text().splitlines()
    test_lines = 0
    functions = []
    k = 0
    while k < len(lines):
        if lines[k].strip() == "#[cfg(test)]":
            end = block_end(lines, k + 1)
            test_lines += end - k + 1
            k = end + 1
            continue
        m = FN.match(lines[k])
        if m:
            end = block_end(lines, k)
            functions.append((m.group(6), k + 1, end - k + 1))
        k += 1
    return len(lines) - test_lines, functions


def arrows():
    meta = json.loads(
        subprocess.check_output(
            ["cargo", "metadata", "--format-version", "1", "--no-deps"], cwd=ROOT
        )
    )
    out = []
    for p in meta["packages"]:
        for d in p["dependencies"]:
            if d["name"].startswith("formcam") and d.get("kind") is None:
                out.append((p["name"], d["name"]))
    return sorted(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--files", type=int, default=500)
    ap.add_argument("--functions", type=int, default=100)
    ap.add_argument("--list", action="store_true")
    args = ap.parse_args()
    files, fns = [], []
    for path in sorted((ROOT / "crates").glob("*/src/**/*.rs")):
        n, f = measure(path)
        rel = path.relative_to(ROOT)
        files.append((n, rel))
        fns.extend((length, f"{rel}:{line}", name) for name, line, length in f)
    big_files = sorted((x for x in files if x[0] > args.files), reverse=True)
    big_fns = sorted((x for x in fns if x[0] > args.functions), reverse=True)
    print(f"source lines (tests left out): {sum(n for n, _ in files)}")
    print(f"files over {args.files} lines: {len(big_files)}")
    print(f"functions over {args.functions} lines: {len(big_fns)}")
    if args.list:
        for n, rel in big_files:
            print(f"  {n:5} {rel}")
        for n, at, name in big_fns:
            print(f"  {n:5} {at} {name}")
    a = arrows()
    print(f"crate arrows: {len(a)}")
    if args.list:
        for src, dst in a:
            print(f"  {src} -> {dst}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
