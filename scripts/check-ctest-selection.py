#!/usr/bin/python3
"""Fails when a ctest entry runs no test case.

ctest splits a test name at ';' (a CMake list separator) and doctest's --test-case filter treats ','
and wildcards specially, so a test whose name holds such characters can turn into entries that select
zero doctest cases and still show "Passed". For every ctest entry that runs a doctest executable with
--test-case=..., this asks the executable how many cases the filter selects (doctest's --count) and
fails unless it is exactly one. Usage: check-ctest-selection.py BUILD_DIR
"""
import json
import re
import subprocess
import sys


def main() -> int:
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    listing = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"], check=True,
                             capture_output=True, text=True).stdout
    tests = json.loads(listing)["tests"]
    bad, checked = [], 0
    for t in tests:
        cmd = t.get("command") or []
        if not any(a.startswith("--test-case=") for a in cmd):
            continue
        out = subprocess.run(cmd + ["--count"], capture_output=True, text=True).stdout
        m = re.search(r"passing the current filters: (\d+)", out)
        n = int(m.group(1)) if m else -1
        checked += 1
        if n != 1:
            bad.append(f"  {t['name']!r}: selects {n} test cases ({' '.join(cmd[1:])})")
    if bad:
        print(f"{len(bad)} of {checked} ctest entries do not select exactly one doctest case:")
        print("\n".join(bad))
        return 1
    print(f"all {checked} doctest ctest entries select exactly one test case")
    return 0


if __name__ == "__main__":
    sys.exit(main())
