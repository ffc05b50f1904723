#!/usr/bin/python3
"""Fails when a ctest entry runs no test case.

ctest splits a test name at ';' (a CMake list separator) and doctest's --test-case filter treats ','
and wildcards specially, so a test whose name holds such characters can turn into entries that select
zero doctest cases and still show "Passed". For every ctest entry that runs a doctest executable with
--test-case=..., this asks the executable how many cases the filter selects (doctest's --count) and
fails unless it is exactly one. The Python package's entries (label python: `python3 -m pytest FILE`,
never --test-case=) are not doctest entries; each must collect at least one pytest test (a file
pytest cannot import collects none and fails ctest anyway, but a renamed test file would be missed).
Usage: check-ctest-selection.py BUILD_DIR
"""
import json
import os
import re
import subprocess
import sys


def main() -> int:
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    listing = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"], check=True,
                             capture_output=True, text=True).stdout
    tests = json.loads(listing)["tests"]
    bad, checked = [], 0
    pytest_bad, pytest_checked = [], 0
    for t in tests:
        cmd = t.get("command") or []
        if "pytest" in cmd and "-m" in cmd:
            env, cwd = dict(os.environ), None
            for p in t.get("properties", []):
                if p.get("name") == "ENVIRONMENT":
                    env.update(v.split("=", 1) for v in p["value"])
                if p.get("name") == "WORKING_DIRECTORY":
                    cwd = p["value"]
            # without --basetemp: pytest empties that folder, and the entry itself may be running now
            collect = [a for a in cmd if not a.startswith("--basetemp")] + ["--collect-only"]
            out = subprocess.run(collect, capture_output=True, text=True, env=env, cwd=cwd).stdout
            m = re.search(r"(\d+) tests? collected", out) or re.search(r"^[^\n]*\.py: (\d+)$", out, re.M)
            pytest_checked += 1
            if not m or int(m.group(1)) < 1:
                pytest_bad.append(f"  {t['name']!r}: collects no pytest test ({' '.join(cmd[1:])})")
            continue
        if not any(a.startswith("--test-case=") for a in cmd):
            continue
        out = subprocess.run(cmd + ["--count"], capture_output=True, text=True).stdout
        m = re.search(r"passing the current filters: (\d+)", out)
        n = int(m.group(1)) if m else -1
        checked += 1
        if n != 1:
            bad.append(f"  {t['name']!r}: selects {n} test cases ({' '.join(cmd[1:])})")
    if pytest_bad:
        print(f"{len(pytest_bad)} of {pytest_checked} pytest ctest entries collect no test:")
        print("\n".join(pytest_bad))
    if bad:
        print(f"{len(bad)} of {checked} ctest entries do not select exactly one doctest case:")
        print("\n".join(bad))
    if bad or pytest_bad:
        return 1
    print(f"all {checked} doctest ctest entries select exactly one test case; "
          f"all {pytest_checked} pytest entries collect tests")
    return 0


if __name__ == "__main__":
    sys.exit(main())
