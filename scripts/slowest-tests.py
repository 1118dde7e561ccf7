#!/usr/bin/env python3
"""Prints the slowest tests of a CTest run, from the JUnit file `ctest --output-junit FILE` writes.

    python3 scripts/slowest-tests.py build/ctest-junit.xml [COUNT]

COUNT (15) tests, slowest first, with their seconds, and the run's total. A test past the fast tier's budget
of 60 s a test (README, "Tests") is marked, so that a developer sees what to split or move to a long tier;
the run's result is CTest's, not this script's: it exits 0 whenever it could read the file.
"""
import sys
import xml.etree.ElementTree as ElementTree

BUDGET_SECONDS = 60.0


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    count = int(argv[2]) if len(argv) == 3 else 15
    try:
        cases = ElementTree.parse(argv[1]).getroot().iter("testcase")
    except (OSError, ElementTree.ParseError) as error:
        print(f"slowest-tests: {argv[1]}: {error}", file=sys.stderr)
        return 2
    times = sorted(((float(case.get("time", 0.0)), case.get("name", "?")) for case in cases), reverse=True)
    total = sum(seconds for seconds, _ in times)
    print(f"The {min(count, len(times))} slowest of {len(times)} tests ({total:,.0f} s of tests in all):")
    for seconds, name in times[:count]:
        mark = f"  <- over the {BUDGET_SECONDS:.0f} s budget" if seconds > BUDGET_SECONDS else ""
        print(f"{seconds:8.1f} s  {name}{mark}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
