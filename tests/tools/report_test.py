#!/usr/bin/python3
"""Checks tools/report.py on a campaign: runs it on DIR, then recomputes from DIR/campaign.h5,
with plain code of its own, the run status counts and per detector the detection and
isolation counts and rates, their Wilson (1927) intervals, the confusion matrix, the
false alarms and hours on intact runs with the Poisson interval's defining equations, and
the median delay, and compares them with DIR/report.json (counts exactly, the rest to 1e-9
relative, the Poisson bounds to 1e-7). Also checks that report.html and every image it
shows exist.

    tests/tools/report_test.py DIR

Exit 0 when everything matches, else 1 after printing each mismatch.
"""

import json
import math
import re
import statistics
import subprocess
import sys
from pathlib import Path

import h5py

REPORT = Path(__file__).resolve().parents[2] / "tools" / "report.py"
Z = 1.959963984540054


def close(a, b, rel=1e-9) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def strings(dataset):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in dataset[()]]


def poisson_cdf(k: int, mean: float) -> float:
    """P(X <= k) for X ~ Poisson(mean), by direct summation."""
    term = total = math.exp(-mean)
    for i in range(1, k + 1):
        term *= mean / i
        total += term
    return total


def check(directory: Path) -> list[str]:
    errors = []

    def expect(what, got, want, rel=None):
        ok = got == want if rel is None else close(got, want, rel)
        if not ok:
            errors.append(f"{what}: report says {got!r}, expected {want!r}")

    done = subprocess.run([sys.executable, str(REPORT), str(directory)], capture_output=True,
                          text=True)
    if done.returncode != 0:
        return [f"report.py exited with {done.returncode}: {done.stderr.strip()}"]
    report = json.loads((directory / "report.json").read_text(),
                        parse_constant=lambda c: errors.append(f"report.json holds {c}"))

    with h5py.File(directory / "campaign.h5", "r") as h5:
        runs = h5["runs"]
        status = strings(runs["status"])
        line = [int(v) for v in runs["failure_line"][()]]
        failure_time = [float(v) for v in runs["failure_time"][()]]
        simulated = [float(v) for v in runs["simulated_time"][()]]
        block = strings(runs["block"])
        lines = int(h5.attrs["num_lines"])
        detectors = h5.attrs.get("detectors", "")
        if isinstance(detectors, bytes):  # fixed-length strings come back as bytes
            detectors = detectors.decode()
        labels = [d for d in str(detectors).split("\n") if d]
        columns = {label: {key: list(runs[f"{label}.{key}"][()]) for key in
                           ("alarm_time", "isolated_line", "delay", "false_alarms")}
                   for label in labels}
        station = ({key: [float(v) for v in runs[key][()]] for key in
                    ("heading_error_max_deg", "thrust_saturated_share")}
                   if "heading_error_max_deg" in runs else None)
        verdict_keys = ("isolation_delay", "final_line", "alarm_seconds_before_failure")
        for label in labels:
            if all(f"{label}.{key}" in runs for key in verdict_keys):
                columns[label].update({key: list(runs[f"{label}.{key}"][()])
                                       for key in verdict_keys})

    counts = {}
    for s in status:
        counts[s] = counts.get(s, 0) + 1
    expect("status counts", report["runs"]["status"], counts)
    # Station keeping per block, over the ok runs (older tables have no such columns).
    if station is None:
        expect("station keeping", report["runs"].get("station_keeping"), None)
    else:
        for b in sorted(set(block)):
            rows = [i for i in range(len(status)) if block[i] == b and status[i] == "ok"]
            got = report["runs"]["station_keeping"].get(b, {})
            errors_ = sorted(station["heading_error_max_deg"][i] for i in rows)
            shares = sorted(station["thrust_saturated_share"][i] for i in rows)
            expect(f"{b} station runs", got.get("runs"), len(rows))
            expect(f"{b} heading lost", got.get("heading_lost"), sum(e > 10.0 for e in errors_))
            if rows:
                expect(f"{b} heading error median", got.get("heading_error_max_deg_median"),
                       statistics.median(errors_), 1e-12)
                expect(f"{b} saturated median", got.get("thrust_saturated_share_median"),
                       statistics.median(shares), 1e-12)
    failure_runs = [i for i in range(len(status)) if status[i] == "ok" and line[i] > 0
                    and math.isfinite(failure_time[i])]
    intact_runs = [i for i in range(len(status)) if status[i] == "ok" and line[i] == 0]
    expect("detectors", sorted(report["detectors"]), sorted(labels))

    for label in labels:
        got, col = report["detectors"].get(label, {}), columns[label]
        detected = [i for i in failure_runs if math.isfinite(col["alarm_time"][i])]
        isolated = [i for i in failure_runs if col["isolated_line"][i] == line[i]]
        n = len(failure_runs)
        for what, k in (("detection", len(detected)), ("isolation", len(isolated))):
            entry = got.get(what, {})
            expect(f"{label} {what} k", entry.get("k"), k)
            expect(f"{label} {what} n", entry.get("n"), n)
            rate = k / n if n else None
            expect(f"{label} {what} rate", entry.get("rate"), rate, 1e-9)
            if n:
                p, z2 = rate, Z * Z
                centre = (p + z2 / (2 * n)) / (1 + z2 / n)
                half = Z * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n)) / (1 + z2 / n)
                expect(f"{label} {what} low", entry.get("low"), max(0.0, centre - half), 1e-9)
                expect(f"{label} {what} high", entry.get("high"), min(1.0, centre + half), 1e-9)

        # The fake campaigns judge no sensor faulty: the column before "missed" stays 0.
        confusion = [[0] * (lines + 2) for _ in range(lines)]
        for i in failure_runs:
            named = col["isolated_line"][i]
            if not (math.isfinite(col["alarm_time"][i]) and 1 <= named <= lines):
                named = lines + 2
            if 1 <= line[i] <= lines:
                confusion[line[i] - 1][named - 1] += 1
        expect(f"{label} confusion", got.get("confusion"), confusion)

        intact = got.get("false_alarms_per_hour", {}).get("intact", {})
        count = sum(int(col["false_alarms"][i]) for i in intact_runs)
        hours = sum(simulated[i] for i in intact_runs) / 3600
        expect(f"{label} intact false alarms", intact.get("count"), count)
        expect(f"{label} intact hours", intact.get("hours"), hours, 1e-9)
        expect(f"{label} intact rate", intact.get("rate"), count / hours if hours else None, 1e-9)
        if hours:  # the exact interval's definition: P(X >= k | low) = P(X <= k | high) = 2.5 %
            low, high = intact.get("low", 0) * hours, intact.get("high", 0) * hours
            expect(f"{label} intact upper bound", poisson_cdf(count, high), 0.025, 1e-7)
            if count:
                expect(f"{label} intact lower bound", 1 - poisson_cdf(count - 1, low), 0.025, 1e-7)
            else:
                expect(f"{label} intact lower bound", low, 0.0)

        verdict = got.get("verdict")
        if "final_line" not in col:
            expect(f"{label} verdict without its columns", verdict, None)
        elif failure_runs or intact_runs:
            named = [i for i in failure_runs if math.isfinite(col["isolation_delay"][i])]
            kept = [i for i in failure_runs if col["final_line"][i] == line[i]]
            verdict = verdict or {}
            for what, k in (("named_after_break", len(named)), ("named_at_end", len(kept))):
                expect(f"{label} {what} k", verdict.get(what, {}).get("k"), k)
                expect(f"{label} {what} n", verdict.get(what, {}).get("n"), len(failure_runs))
            seconds = sum(simulated[i] for i in intact_runs)
            on = sum(float(col["alarm_seconds_before_failure"][i]) for i in intact_runs)
            expect(f"{label} alarm-on share, intact",
                   verdict.get("alarm_on_share", {}).get("intact"),
                   on / seconds if seconds else None, 1e-9)

        blocks = got.get("per_block", {})
        expect(f"{label} blocks", sorted(blocks), sorted(set(block)))
        for b, entry in blocks.items():
            fail = [i for i in failure_runs if block[i] == b]
            quiet = [i for i in intact_runs if block[i] == b]
            expect(f"{label} {b} failure runs", entry.get("failure_runs"), len(fail))
            if fail and "final_line" in col:
                named = [i for i in fail if math.isfinite(col["isolation_delay"][i])]
                expect(f"{label} {b} named after the break",
                       entry.get("named_after_break", {}).get("k"), len(named))
            if quiet:
                count = sum(int(col["false_alarms"][i]) for i in quiet)
                expect(f"{label} {b} false alarms",
                       entry.get("false_alarms_per_hour", {}).get("count"), count)

        # The summary on standard output: one row per detector with its isolation k/n.
        row = [r for r in done.stdout.splitlines() if r.split(" ", 1)[0] == label]
        if n and not (len(row) == 1 and f"({len(isolated)}/{n})" in row[0]):
            errors.append(f"{label}: no summary row with isolation ({len(isolated)}/{n}) in "
                          f"report.py's output")

        delays = sorted(float(col["delay"][i]) for i in detected)
        median = None
        if delays:
            middle = len(delays) // 2
            median = (delays[middle] if len(delays) % 2
                      else (delays[middle - 1] + delays[middle]) / 2)
        expect(f"{label} median delay", got.get("delay", {}).get("median"), median, 1e-9)

    page = directory / "report.html"
    if not page.is_file():
        errors.append(f"{page} is missing")
    else:
        for name in re.findall(r'<img src="([^"]+)"', page.read_text()):
            if not (directory / name).is_file():
                errors.append(f"report.html shows {name}, which is missing")
    return errors


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("usage: report_test.py DIR", file=sys.stderr)
        return 2
    errors = check(Path(argv[0]))
    for error in errors:
        print(f"MISMATCH {error}")
    print("report_test: " + ("ok" if not errors else f"{len(errors)} mismatches"))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
