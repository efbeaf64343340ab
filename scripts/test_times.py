#!/usr/bin/python3
"""Where the test suite's time goes: the slowest tests of one ctest run, from its JUnit report.

    scripts/test_times.py REPORT.xml [--top N] [--wall SECONDS]

scripts/test.sh runs ctest with --output-junit and calls this at the end, so every run of the
suite (CI's included) ends with the tests that cost most, against CI's budget (README "Tests").
Prints the N slowest tests (seconds, status), the number of tests and the sum of their times
(each test counted once, whatever its PROCESSORS); --wall adds the suite's wall time.
Exit status: 0, or 2 when the report is missing or not a JUnit report.
"""
import argparse
import sys
import xml.etree.ElementTree as ET


#: ctest's <testcase status=...> in words (CMake 3.21+); a <skipped> child (a test that exited
#: with its SKIP_RETURN_CODE) makes it 'skipped'
_STATUS = {"run": "passed", "fail": "failed", "notrun": "not run", "disabled": "disabled"}


def read_times(path):
    """[(name, seconds, status)] of every <testcase> in a ctest JUnit report; status is
    'passed', 'failed', 'skipped', 'not run' or 'disabled'."""
    root = ET.parse(path).getroot()
    if root.tag not in ("testsuite", "testsuites"):
        raise ValueError(f"'{path}' is not a JUnit report (root element <{root.tag}>)")
    rows = []
    for case in root.iter("testcase"):
        name = case.get("name", "?")
        try:
            seconds = float(case.get("time", "nan"))
        except ValueError:
            raise ValueError(f"'{path}': test '{name}' has time '{case.get('time')}', "
                             "expected seconds") from None
        status = _STATUS.get(case.get("status"), case.get("status"))
        if case.find("skipped") is not None:
            status = "skipped"
        elif status is None:
            status = "failed" if case.find("failure") is not None else "passed"
        rows.append((name, seconds, status))
    return rows


def summary(rows, top, wall_s=None):
    """The report's text: the `top` slowest tests and the totals."""
    ordered = sorted(rows, key=lambda r: r[1], reverse=True)
    total = sum(r[1] for r in rows)
    lines = [f"test times: the {min(top, len(rows))} slowest of {len(rows)} tests "
             f"(sum of all test times {total:.0f} s"
             + (f", suite wall time {wall_s:.0f} s" if wall_s is not None else "") + ")"]
    for name, seconds, status in ordered[:top]:
        share = f"{100.0 * seconds / total:4.1f} %" if total > 0 else "  -  "
        lines.append(f"  {seconds:8.1f} s  {share}  {name}" + ("" if status == "passed"
                                                              else f"  [{status}]"))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("report", help="ctest's JUnit report (ctest --output-junit FILE)")
    ap.add_argument("--top", type=int, default=15, help="how many tests to list (default 15)")
    ap.add_argument("--wall", type=float, help="the suite's wall time [s], printed beside")
    args = ap.parse_args(argv)
    if args.top < 1:
        ap.error(f"--top {args.top}: expected a positive number of tests")
    try:
        rows = read_times(args.report)
    except (OSError, ET.ParseError, ValueError) as e:
        print(f"test_times: {e}", file=sys.stderr)
        return 2
    print(summary(rows, args.top, args.wall))
    return 0


if __name__ == "__main__":
    sys.exit(main())
