#!/usr/bin/env python3
"""Run a command and judge it by its exit status AND its output.

ctest's PASS_REGULAR_EXPRESSION replaces the exit status as the verdict: a
command that fails while printing the expected words passes. Tests that also
want a pattern in the output run through this wrapper instead
(cmake/HofemOutputTest.cmake, hofem_output_test): the test fails when the
exit status is not the expected one (0 unless --exit says otherwise) or when
the pattern is not found in its output. As under ctest, stdout and stderr
share one pipe, so the output interleaves them in the order they reached it;
the pattern is searched as CMake's regular expressions are (anywhere in the
output, '.' matching a newline), so patterns written for
PASS_REGULAR_EXPRESSION carry over.

--exit nonzero means "exited with a status other than 0": a command killed by
a signal (a crash) fails it, as it would fail any other expectation, so a test
of a refusal cannot pass on a segfault (ctest's WILL_FAIL would).
--skip-exit N passes the command's status N through untouched, whatever it
printed, so that ctest's SKIP_RETURN_CODE N still marks the test skipped.

usage: expect_output.py --regex=PATTERN [--exit N|nonzero] [--skip-exit N]
                        [--stdin FILE] -- COMMAND [ARG...]
(--regex=PATTERN with '=': a pattern may start with '-')
"""
import argparse
import re
import subprocess
import sys


def describe(status):
    # subprocess gives -N for "killed by signal N"; say so rather than print a negative status.
    return f"killed by signal {-status}" if status < 0 else f"exit status {status}"


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--regex", required=True, help="pattern that must occur in the output")
    ap.add_argument("--exit", default="0", help="expected exit status: a number or 'nonzero' (default 0)")
    ap.add_argument("--skip-exit", type=int, help="status passed straight through (ctest SKIP_RETURN_CODE)")
    ap.add_argument("--stdin", help="file fed to the command's standard input")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args(argv)
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    if not cmd:
        ap.error("no command after --")
    if a.exit != "nonzero" and not a.exit.isdigit():
        ap.error(f"--exit {a.exit!r}: expected a number 0..255 or 'nonzero'")
    pattern = re.compile(a.regex, re.DOTALL)
    try:
        stdin = open(a.stdin, "rb") if a.stdin else subprocess.DEVNULL
        # One pipe for both streams, as ctest gives a test (a pattern may span a
        # warning on stderr and the report on stdout, e.g. cli.mesh_reorient).
        p = subprocess.run(cmd, stdin=stdin, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    except OSError as e:
        print(f"expect_output: FAIL: cannot run {cmd[0]}: {e}")
        return 2
    # The command's own bytes, unchanged, for ctest's log.
    sys.stdout.flush()
    sys.stdout.buffer.write(p.stdout)
    sys.stdout.buffer.flush()
    if a.skip_exit is not None and p.returncode == a.skip_exit:
        print(f"expect_output: SKIP (exit {p.returncode})")
        return p.returncode
    output = p.stdout.decode(errors="replace")
    verdicts = []
    status_ok = p.returncode > 0 if a.exit == "nonzero" else p.returncode == int(a.exit)
    if not status_ok:
        verdicts.append(f"{describe(p.returncode)}, expected {a.exit}")
    if not pattern.search(output):
        verdicts.append(f"the output does not match {a.regex!r}")
    if verdicts:
        print("expect_output: FAIL: " + "; ".join(verdicts))
        return 1
    print(f"expect_output: OK ({describe(p.returncode)}, pattern found)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
