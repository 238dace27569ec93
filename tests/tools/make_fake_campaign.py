#!/usr/bin/python3
"""Writes a small synthetic campaign.h5, in the layout `moorsim batch` writes, into DIR.

    tests/tools/make_fake_campaign.py DIR [--case CASE]

Every run gets a made-up alarm statistic per detector, sampled at 1 s; the per-run
columns (alarm time, isolated line, delay, false alarms, maximum before the failure) and
the threshold-grid tables are all derived from it, so the file is self-consistent.

Standard case: 4 mooring lines; lines 1 and 2 fail in 5 seeds each (block "failures",
factors environment.current.profile[1].speed in {0, 0.1} and failure.time uniform in
300-900 s), 3 intact runs (block "intact"), run 3 failed. Detectors: dht (misses one run,
false alarms on some), mle (names a wrong line once), glr (never reaches its threshold).
The verdict columns (isolation_delay, final_line, alarm_seconds_before_failure) follow the
first onset, except that every fifth failure run's verdict is revised to the failed line 20 s
later and every third one ends without naming it. Other cases, for the report's edge cases:
no-intact, no-failure, no-detectors, all-failed, single, no-factors, no-verdict (a campaign
written before the verdict columns existed).
"""

import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

CASES = ("standard", "no-intact", "no-failure", "no-detectors", "all-failed", "single",
         "no-factors", "no-verdict")
DURATION = 1200.0
NUM_LINES = 4
# label: (type, statistic text, threshold, grid)
DETECTORS = {
    "dht": ("dht", "largest posterior probability of a failure hypothesis", 0.9,
            np.linspace(0.5, 1.0, 11)),
    "mle": ("mle", "log-likelihood gap of the best failure hypothesis over intact", 20.0,
            np.linspace(0.0, 60.0, 13)),
    "glr": ("glr", "largest generalised likelihood ratio statistic", 150.0,
            np.linspace(0.0, 200.0, 21)),
}


def statistic(label, rng, t, failure_time, run):
    """A made-up statistic: noise around a base level, a short spike before the failure in
    some runs, and a ramp after the failure."""
    threshold = DETECTORS[label][2]
    s = threshold * (0.3 + 0.05 * rng.standard_normal(t.size))
    if label == "dht" and run % 3 == 0:  # a false alarm: 4 s above the threshold
        start = int(0.3 * (failure_time if np.isfinite(failure_time) else t[-1]))
        s[start:start + 4] = 1.05 * threshold
    if np.isfinite(failure_time):
        after = t >= failure_time
        slope = {"dht": 0.02, "mle": 0.5, "glr": 0.6}[label] * (1 + 0.3 * rng.random())
        if label == "dht" and run == 5:
            slope = 0.0  # missed
        s[after] += slope * threshold / 10 * (t[after] - failure_time)
        if label == "glr":
            s = np.minimum(s, 0.8 * threshold)
        if label == "dht":
            s = np.minimum(s, 0.999)
    return s


def onsets(above):
    return above & ~np.r_[False, above[:-1]]


def derive(s, t, failure_time, threshold, grid):
    failure = np.isfinite(failure_time)
    before = t < failure_time if failure else np.ones(t.size, bool)
    after = t >= failure_time if failure else np.zeros(t.size, bool)
    above = s >= threshold
    false_alarms = int((onsets(above) & before).sum())
    hits = t[above & after] if failure else t[above]
    alarm = float(hits[0]) if hits.size else np.nan
    crossings = [int((onsets(s >= g) & before).sum()) for g in grid]
    first = [float(t[(s >= g) & after][0]) if ((s >= g) & after).any() else np.nan
             for g in grid]
    peak = float(s[before].max()) if before.any() else np.nan
    return alarm, false_alarms, peak, crossings, first


def make_runs(case):
    runs = []
    for line in (1, 2):
        for seed in range(1, 6):
            runs.append({"block": "failures", "seed": 1000 + 10 * line + seed, "line": line})
    for seed in range(1, 4):
        runs.append({"block": "intact", "seed": 2000 + seed, "line": 0})
    if case == "no-intact":
        runs = [r for r in runs if r["line"]]
    elif case == "no-failure":
        runs = [r for r in runs if not r["line"]]
    elif case == "single":
        runs = runs[:1]
    return runs


def write(directory: Path, case: str) -> Path:
    rng = np.random.default_rng(7)
    runs = make_runs(case)
    detectors = {} if case == "no-detectors" else DETECTORS
    columns = {k: [] for k in ("run", "block", "seed", "status", "error", "command",
                               "failure_line", "failure_time", "failure_mode", "duration",
                               "simulated_time", "wall_time", "speed", "ftime")}
    per = {label: {k: [] for k in ("alarm_time", "isolated_line", "delay", "false_alarms",
                                   "max_before_failure", "crossings", "first",
                                   "isolation_delay", "final_line",
                                   "alarm_seconds_before_failure")}
           for label in detectors}
    for index, spec in enumerate(runs):
        line = spec["line"]
        failure_time = float(rng.uniform(300, 900)) if line else np.nan
        failed = case == "all-failed" or (case == "standard" and index == 3)
        simulated = 412.0 if failed else DURATION
        t = np.arange(0.0, simulated + 0.5, 1.0)
        speed = 0.1 * (index % 2)
        command = (f"moorsim run campaigns/fake.yaml --block {spec['block']} --seed "
                   f"{spec['seed']} --set environment.current.profile[1].speed={speed:g}"
                   + (f" --set failure.time={failure_time:.6g}" if line else "")
                   + f" --out 'runs/{index:04d} <x&y>'")
        for key, value in (("run", index), ("block", spec["block"]), ("seed", spec["seed"]),
                           ("status", "failed" if failed else "ok"),
                           ("error", "integrator failed at t = 412 s (CVODE flag -4)"
                            if failed else ""), ("command", command), ("failure_line", line),
                           ("failure_time", failure_time),
                           ("failure_mode", "anchor chain parts" if line else ""),
                           ("duration", DURATION), ("simulated_time", simulated),
                           ("wall_time", 30.0 + rng.random()), ("speed", speed),
                           ("ftime", failure_time)):
            columns[key].append(value)
        for label, (_, _, threshold, grid) in detectors.items():
            s = statistic(label, rng, t, failure_time, index)
            alarm, false_alarms, peak, crossings, first = derive(s, t, failure_time, threshold,
                                                                 grid)
            named = 0
            if np.isfinite(alarm):
                named = line if line else 1 + index % NUM_LINES
                if label == "mle" and index == 7:
                    named = line % NUM_LINES + 1  # a wrong line
            out = per[label]
            out["alarm_time"].append(alarm)
            out["isolated_line"].append(named)
            out["delay"].append(alarm - failure_time if line else np.nan)
            out["false_alarms"].append(false_alarms)
            out["max_before_failure"].append(peak)
            delay = alarm - failure_time if line else np.nan
            if line and named != line and index % 5 == 0 and np.isfinite(alarm):
                delay += 20.0  # revised to the failed line later
            elif line and named != line:
                delay = np.nan
            out["isolation_delay"].append(delay)
            out["final_line"].append(0 if (index % 3 == 0 or not np.isfinite(alarm)) else
                                     (line if np.isfinite(delay) else named))
            out["alarm_seconds_before_failure"].append(10.0 * false_alarms + 0.5 * index)
            out["crossings"].append(crossings)
            out["first"].append(first)

    directory.mkdir(parents=True, exist_ok=True)
    path = directory / "campaign.h5"
    strings = h5py.string_dtype()
    factors = [] if case == "no-factors" else ["environment.current.profile[1].speed",
                                               "failure.time"]
    with h5py.File(path, "w") as h5:
        h5.attrs["campaign"] = "name: fake\nblocks:\n  - name: failures\n  - name: intact\n"
        h5.attrs["campaign_name"] = f"fake campaign ({case}) <&>"
        h5.attrs["campaign_path"] = "campaigns/fake.yaml"
        h5.attrs["version"] = "0.0.0-test"
        h5.attrs["command_line"] = "moorsim batch campaigns/fake.yaml --out fake"
        h5.attrs["campaign_seed"] = np.uint64(18446744073709551557)
        h5.attrs["num_lines"] = np.int64(NUM_LINES)
        h5.attrs["factors"] = "\n".join(factors)
        h5.attrs["detectors"] = "\n".join(detectors)
        g = h5.create_group("runs")
        types = {"run": np.int64, "seed": np.uint64, "failure_line": np.int64}
        for key, values in columns.items():
            name = {"speed": factors[0] if factors else None,
                    "ftime": factors[1] if factors else None}.get(key, key)
            if name is None:
                continue
            if isinstance(values[0] if values else "", str):
                g.create_dataset(name, data=np.array(values, dtype=object), dtype=strings)
            else:
                g.create_dataset(name, data=np.array(values, dtype=types.get(key, np.float64)))
        for label, (kind, text, threshold, grid) in detectors.items():
            out = per[label]
            for key in ("alarm_time", "delay", "max_before_failure"):
                g.create_dataset(f"{label}.{key}", data=np.array(out[key], dtype=np.float64))
            for key in ("isolated_line", "false_alarms"):
                g.create_dataset(f"{label}.{key}", data=np.array(out[key], dtype=np.int64))
            if case != "no-verdict":
                for key in ("isolation_delay", "alarm_seconds_before_failure"):
                    g.create_dataset(f"{label}.{key}", data=np.array(out[key], dtype=np.float64))
                g.create_dataset(f"{label}.final_line",
                                 data=np.array(out["final_line"], dtype=np.int64))
            d = h5.create_group(f"detectors/{label}")
            d.attrs["type"], d.attrs["statistic"] = kind, text
            d.attrs["threshold"] = np.float64(threshold)
            d.create_dataset("thresholds", data=grid)
            d.create_dataset("false_crossings", data=np.array(out["crossings"], dtype=np.int64)
                             .reshape(len(runs), grid.size))
            d.create_dataset("first_crossing", data=np.array(out["first"], dtype=np.float64)
                             .reshape(len(runs), grid.size))
    return path


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", type=Path, metavar="DIR")
    parser.add_argument("--case", choices=CASES, default="standard")
    args = parser.parse_args(argv)
    print(f"wrote {write(args.dir, args.case)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
