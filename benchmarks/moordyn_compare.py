#!/usr/bin/env python3
"""The fairlead tensions of one MoorDyn input file as MoorDyn and moorsim computed them.

    moordyn_compare.py MOORDYN_INPUT SCENARIO MOORDYN.csv MOORSIM.csv FROM

MOORDYN.csv is benchmarks/moordyn_driver.cc's output (time, then per coupled point in
MoorDyn's order the force its lines exert on it); MOORSIM.csv is `moorsim simulate-lines
--out` of the scenario `moorsim import moordyn` wrote of the same file (time, then per
moorsim line its fairlead tension). A coupled point is compared with the one moorsim line
that ends at it (the scenario's comments name each line's MoorDyn points); a point where
several lines end is left out (moorsim writes each line's tension, MoorDyn their sum).
Prints the worst point's RMS difference over t >= FROM as a % of MoorDyn's range there
and, in brackets, as a % of MoorDyn's mean tension there (the range can be small: a line
across the motion barely feels it), or "-" and why not.
"""
import csv
import math
import re
import sys


def coupled_points(path):
    """MoorDyn's coupled (vessel) point ids, in the order of its points table."""
    ids, table, rows = [], False, 0
    with open(path, errors="replace") as f:
        for line in f:
            if line.lstrip().startswith("--"):
                table = bool(re.search(r"POINT|CONNECTION|NODE PROP", line.upper()))
                rows = 0
                continue
            if not table or not line.strip():
                continue
            rows += 1
            fields = line.split()
            if rows > 2 and len(fields) > 1 and fields[1].lower() in ("vessel", "coupled"):
                ids.append(fields[0])
    return ids


def fairleads(scenario):
    """moorsim line number -> the MoorDyn point its upper end is, from the comments."""
    ends = {}
    with open(scenario) as f:
        for line in f:
            m = re.match(r"\s*- id: (\d+)\s+# MoorDyn lines? .*: point .* -> (\S+)\s*$", line)
            if m:
                ends[int(m.group(1))] = m.group(2)
    return ends


def read(path):
    with open(path) as f:
        rows = [r for r in csv.reader(l for l in f if not l.startswith("#"))]
    return rows[0], {round(float(r[0]), 3): [float(v) for v in r[1:]] for r in rows[1:]}


def main():
    md_input, scenario, md_csv, ms_csv, start = sys.argv[1:6]
    start = float(start)
    points = coupled_points(md_input)
    ends = fairleads(scenario)
    _, md = read(md_csv)
    header, ms = read(ms_csv)
    worst, of_mean, compared = 0.0, 0.0, 0
    for i, point in enumerate(points):
        lines = [k for k, p in ends.items() if p == point]
        if len(lines) != 1:
            continue
        column = header.index(f"line{lines[0]}") - 1
        times = [t for t in md if t >= start - 1e-9 and t in ms]
        if len(times) < 10:
            continue
        ref = [md[t][i] for t in times]
        span = max(ref) - min(ref)
        rms = math.sqrt(sum((ms[t][column] - md[t][i]) ** 2 for t in times) / len(times))
        if span > 0.0:
            if 100.0 * rms / span >= worst:
                worst = 100.0 * rms / span
                of_mean = 100.0 * rms / abs(sum(ref) / len(ref))
            compared += 1
    if compared == 0:
        print("- (no coupled point with one line)")
    else:
        print(f"{worst:.2f} ({of_mean:.2f})")


if __name__ == "__main__":
    main()
