#!/usr/bin/python3
"""Compares two builds' s2sim-peers rounds (the --rounds-csv files of alternating runs).

    bench/peers/compare_rounds.py BEFORE_GLOB AFTER_GLOB

For each scene and engine, over every round of every file: the median and the fastest round
of each build and their ratios (after / before). The serial engine is read in thread CPU time,
the parallel ones in wall time (what two threads save is wall time).
"""

import csv
import glob
import statistics
import sys


def rounds(pattern):
    """(scene, engine) -> every round's time, in the files' order."""
    found = {}
    files = sorted(glob.glob(pattern))
    if not files:
        sys.exit(f"compare_rounds: no file matches {pattern}")
    for name in files:
        with open(name, newline="") as f:
            for row in csv.DictReader(f):
                column = "cpu_us" if row["engine"] == "s2sim" else "wall_us"
                found.setdefault((row["scene"], row["engine"]), []).append(float(row[column]))
    return found


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    before, after = rounds(argv[1]), rounds(argv[2])
    print(f"{'scene':<12} {'engine':<12} {'time':<5} {'before':>8} {'after':>8} {'ratio':>6} |"
          f" {'fastest':>8} {'fastest':>8} {'ratio':>6} {'rounds':>6}")
    for key, b in before.items():
        a = after.get(key)
        if not a:
            continue
        kind = "cpu" if key[1] == "s2sim" else "wall"
        mb, ma = statistics.median(b), statistics.median(a)
        print(f"{key[0]:<12} {key[1]:<12} {kind:<5} {mb:8.2f} {ma:8.2f} {ma / mb:6.3f} |"
              f" {min(b):8.2f} {min(a):8.2f} {min(a) / min(b):6.3f} {min(len(a), len(b)):6d}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
