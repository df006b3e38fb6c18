#!/usr/bin/env python3
"""Puts the columns of several runs' timeseries.csv side by side in one CSV, each column named
after its run (NAME.column), so that `beltsim plot` draws the runs in one picture:

    python3 media/merge_runs.py OUT.csv NAME=RUN/timeseries.csv NAME=RUN/timeseries.csv ...

The runs must share their sample times (the same script and `sample`); a run that differs in its
times is refused, naming the first row that differs."""
import csv
import sys


def main(out, runs):
    tables = []
    for arg in runs:
        name, _, path = arg.partition("=")
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        tables.append((name, path, rows[0], rows[1:]))
    times = [row[0] for row in tables[0][3]]
    for name, path, header, rows in tables[1:]:
        other = [row[0] for row in rows]
        if other != times:
            k = next((k for k, (a, b) in enumerate(zip(times, other)) if a != b), min(len(times), len(other)))
            sys.exit(f"merge_runs: {path} has other sample times than {tables[0][1]} (row {k + 2})")
    with open(out, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["t"] + [f"{name}.{col}" for name, _, header, _ in tables for col in header[1:]])
        for k, t in enumerate(times):
            w.writerow([t] + [v for _, _, _, rows in tables for v in rows[k][1:]])


if __name__ == "__main__":
    if len(sys.argv) < 4 or any("=" not in a for a in sys.argv[2:]):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
