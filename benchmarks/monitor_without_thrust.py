#!/usr/bin/env python3
"""What the monitor's detectors do without a thrust feed, over a campaign's runs.

Each run of the campaign (thesis_detection_small: every line parting at its fairlead at a
random time, with and without the thesis's current, 3 seeds each, and an intact hour per
current) is played by `moorsim stream` into a tagged NMEA log, and the log replayed through
two monitors of the same vessel: one given the thrust (XDR), one without a thrust feed. Per
detector and condition: the share of failures detected and isolated (Wilson 95 % interval),
the median delay, and the false alarms (onsets before the failure, or in the intact hours)
per hour watched.

    benchmarks/monitor_without_thrust.py [--campaign FILE] [--jobs N] [--out FILE.json]

MOORSIM (default build/release/tools/moorsim) is the program measured.
"""
import argparse
import concurrent.futures
import json
import math
import os
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MOORSIM = os.environ.get("MOORSIM", os.path.join(ROOT, "build/release/tools/moorsim"))
LIBRARY = os.path.join(ROOT, "scenarios/library")


def runs_of(campaign):
    """The campaign's runs from `moorsim batch --dry-run`: seed, duration, overrides."""
    listing = subprocess.run([MOORSIM, "batch", campaign, "--dry-run"], check=True,
                             capture_output=True, text=True).stdout.splitlines()
    header = next(i for i, line in enumerate(listing) if line.startswith("run\t"))
    runs = []
    for line in listing[header + 1:]:
        cells = line.split("\t")
        if len(cells) < 6:
            continue
        factors = dict(f.split("=", 1) for f in cells[5].split())
        runs.append({"index": int(cells[0]), "block": cells[1], "seed": cells[2],
                     "duration": float(cells[4].split()[0]), "factors": factors})
    return runs


def config(scenario, thrust):
    text = (f"scenario: {scenario}\norigin: {{latitude_deg: 61.25, longitude_deg: 1.75}}\n"
            "antenna: [40, -5, -30]\nfeeds:\n  - {name: log, file: {path: trial.nmea}}\n")
    if thrust:
        text += "thrust: {feed: log, transducers: [TX, TY, TN]}\n"
    return text + f"store: store-{'with' if thrust else 'without'}\n" + \
        f"alarms: alarms-{'with' if thrust else 'without'}.jsonl\n"


def play(run):
    with tempfile.TemporaryDirectory() as work:
        current = float(run["factors"].get("environment.current.profile[1].speed", "0"))
        vessel = os.path.join(LIBRARY, "thesis_no_failure_current.yaml" if current > 0
                              else "thesis_no_failure.yaml")
        for thrust in (True, False):
            with open(os.path.join(work, f"{thrust}.yaml"), "w") as f:
                f.write(config(vessel, thrust))
        sets = ["--set", f"simulation.duration={run['duration']:g}"]
        for key, value in run["factors"].items():
            sets += ["--set", f"{key}={value}"]
        if run["block"] == "failures":
            sets += ["--set", "failure.mode=fairlead"]
        # The campaign's own scenario, with its overrides (the monitor's vessel is the same
        # without the failure: the library's case with the current, or without it for 0).
        played = os.path.join(LIBRARY, "thesis_no_failure_current.yaml")
        subprocess.run([MOORSIM, "stream", played, "--to", os.path.join(work, "True.yaml"),
                        "--seed", run["seed"], "--quiet"] + sets, check=True)
        result = {}
        for thrust in (True, False):
            subprocess.run([MOORSIM, "monitor", os.path.join(work, f"{thrust}.yaml"), "--quiet"],
                           check=True, capture_output=True)
            name = "with" if thrust else "without"
            events = [json.loads(line) for line in open(os.path.join(work, f"alarms-{name}.jsonl"))]
            result[name] = [e for e in events if "alarm" not in e]
        return run, result


def wilson(k, n):
    if n == 0:
        return (float("nan"), float("nan"))
    z, p = 1.96, k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return (max(0.0, centre - half), min(1.0, centre + half))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--campaign",
                        default=os.path.join(ROOT, "scenarios/campaigns/thesis_detection_small.yaml"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out")
    args = parser.parse_args()
    runs = runs_of(args.campaign)
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        played = list(pool.map(play, runs))
    detectors = sorted({e["detector"] for _, result in played for events in result.values()
                        for e in events})
    table = {}
    for run, result in played:
        line = int(run["factors"].get("failure.line", 0)) if run["block"] == "failures" else 0
        failure = float(run["factors"]["failure.time"]) if line else None
        for condition, events in result.items():
            for detector in detectors:
                row = table.setdefault((detector, condition), {
                    "failures": 0, "detected": 0, "isolated": 0, "delays": [],
                    "false_alarms": 0, "hours": 0.0})
                onsets = [e for e in events if e["detector"] == detector and e["event"] == "onset"]
                row["hours"] += (failure if line else run["duration"]) / 3600.0
                row["false_alarms"] += sum(1 for e in onsets if not line or e["time"] < failure)
                if line:
                    row["failures"] += 1
                    after = [e for e in onsets if e["time"] >= failure]
                    if after:
                        row["detected"] += 1
                        row["isolated"] += after[0]["line"] == line
                        row["delays"].append(after[0]["time"] - failure)
    report = []
    print("| detector | thrust feed | detected | isolated | median delay | false alarms per hour |")
    print("|---|---|---|---|---|---|")
    for (detector, condition), row in sorted(table.items()):
        n = row["failures"]
        detected, isolated = wilson(row["detected"], n), wilson(row["isolated"], n)
        delay = statistics.median(row["delays"]) if row["delays"] else float("nan")
        rate = row["false_alarms"] / row["hours"] if row["hours"] else float("nan")
        report.append({"detector": detector, "thrust": condition, **row,
                       "detected_interval": detected, "isolated_interval": isolated,
                       "median_delay": delay, "false_alarms_per_hour": rate})
        print(f"| {detector} | {condition} | {row['detected']}/{n} "
              f"({detected[0]:.2f}-{detected[1]:.2f}) | {row['isolated']}/{n} "
              f"({isolated[0]:.2f}-{isolated[1]:.2f}) | {delay:.0f} s | "
              f"{rate:.2f} ({row['false_alarms']} in {row['hours']:.1f} h) |")
    if args.out:
        with open(args.out, "w") as f:
            json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
