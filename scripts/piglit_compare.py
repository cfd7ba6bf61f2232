#!/usr/bin/env python3
"""Compares piglit results with the expected ones (tests/piglit/expected.txt).

    python3 scripts/piglit_compare.py EXPECTED RESULTS.json.bz2 [MORE.json.bz2 ...] [--ran-only]
    python3 scripts/piglit_compare.py --counts RESULTS.json.bz2 [MORE.json.bz2 ...]

EXPECTED has one test a line, `name,result` (result: pass, fail, skip, warn, timeout, crash),
`#` comments (the reason above each fail, skip and timeout) and blank lines. Later result files
replace the results of earlier ones (piglit.sh re-runs the tests Xvfb refused). Prints every
test whose result differs from the expected one, as a diff (`-` expected, `+` got), then the
counts; the exit status is 1 when a test differs, is missing from the run, or is not in
EXPECTED. With --ran-only, expected tests that did not run are not differences (a subset).
With --counts, only the counts of the results are printed.
"""

import bz2
import collections
import json
import sys


def read_expected(path):
    """The expected result of each test of the file at `path`."""
    expected = {}
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            name, sep, result = line.rpartition(",")
            if not sep or not name:
                sys.exit(f"{path}:{number}: expected `name,result`, found {line!r}")
            if name in expected:
                sys.exit(f"{path}:{number}: {name} is listed twice")
            expected[name] = result
    return expected


def read_results(paths):
    """The result of each test of piglit's results files, later files first."""
    results = {}
    for path in paths:
        with bz2.open(path) if path.endswith(".bz2") else open(path, "rb") as f:
            tests = json.load(f)["tests"]
        results.update({name: t["result"] for name, t in tests.items()})
    return results


def counts_line(results):
    """The counts of each result in `results`."""
    counts = collections.Counter(results.values())
    return f"piglit_compare: {len(results)} tests ran: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))


def main(argv):
    ran_only = "--ran-only" in argv
    args = [a for a in argv if a not in ("--ran-only", "--counts")]
    if "--counts" in argv and args:
        print(counts_line(read_results(args)))
        return 0
    if len(args) < 2:
        sys.exit(__doc__)
    expected = read_expected(args[0])
    results = read_results(args[1:])
    lines = []
    for name in sorted(set(expected) | set(results)):
        want, got = expected.get(name), results.get(name)
        if want == got or (got is None and ran_only):
            continue
        lines.append((name, want, got))
    for name, want, got in lines:
        if want is not None:
            print(f"-{name},{want}")
        print(f"+{name},{got if got is not None else 'not run'}")
    print(counts_line(results))
    if lines:
        print(f"piglit_compare: {len(lines)} tests differ from {args[0]}")
        return 1
    print(f"piglit_compare: every result as expected ({args[0]})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
