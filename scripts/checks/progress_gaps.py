#!/usr/bin/env python3
"""The main job's progress check: the longest silence in its stderr log.

  progress_gaps.py LOG [--max SECONDS]

LOG holds one line per stderr line, "EPOCH_SECONDS text" (scripts/run writes
reports/logs/main_job.log so). Prints the longest gaps between consecutive lines
with the line that ended each, and exits 1 if the longest exceeds --max (default
30 s: a CI log that stays silent longer looks hung)."""
import sys


def main(argv):
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    path, limit = argv[0], 30.0
    if "--max" in argv:
        limit = float(argv[argv.index("--max") + 1])
    stamps = []
    with open(path, errors="replace") as f:
        for line in f:
            head, _, text = line.rstrip("\n").partition(" ")
            if head.isdigit():
                stamps.append((int(head), text))
    if len(stamps) < 2:
        print(f"progress_gaps: {path}: {len(stamps)} timestamped lines, too few to judge")
        return 1
    gaps = sorted(((b[0] - a[0], b[1]) for a, b in zip(stamps, stamps[1:])), reverse=True)
    total = stamps[-1][0] - stamps[0][0]
    print(f"progress_gaps: {len(stamps)} lines over {total} s; longest silences (limit {limit:g} s):")
    for gap, text in gaps[:5]:
        print(f"  {gap:4d} s before: {text[:120]}")
    return 1 if gaps[0][0] > limit else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
