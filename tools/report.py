#!/usr/bin/python3
"""Reports a moorsim Monte-Carlo campaign: reads DIR/campaign.h5 (written by `moorsim batch`)
and writes report.html, the PNG figures it shows and report.json (every number shown).

    tools/report.py DIR [--out DIR2]

Per detector: detection and isolation rates (overall, per failed line, per factor level),
the confusion matrix, detection delays, false alarms per hour, ROC curves over the
detector's threshold grid, the run counts by status, the station keeping per block (runs
that left their setpoint heading, flagged) and the worst runs with the command that repeats
each. A campaign with a design section adds its design checks (DIR/design.json): the lines'
MPM tensions and their checks, the offsets and the fatigue lives. All intervals are 95 %: Wilson (1927) score intervals for proportions,
exact (Garwood 1936) intervals for Poisson rates, from scipy's distributions.

A missing directory or file, or a file that is not a campaign, ends the script with a
one-line error naming the file and exit code 2.

Needs Debian's python3-numpy, python3-scipy, python3-h5py and python3-matplotlib
(tools/setup.sh); if
`python3` on PATH is not Debian's, run /usr/bin/python3.
"""

import argparse
import html
import json
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path

try:
    import h5py
    import matplotlib
    import numpy as np
    from scipy.stats import binomtest, chi2
except ImportError as error:
    print(f"report: python module '{error.name}' is missing: install python3-numpy "
          f"python3-scipy python3-h5py python3-matplotlib (tools/setup.sh) and use "
          f"/usr/bin/python3",
          file=sys.stderr)
    sys.exit(1)

EXIT_BAD_INPUT = 2
CONFIDENCE = 0.95
WITHIN = (60.0, 120.0, 300.0)  # s, the ROC's detection deadlines
MAX_LEVELS = 8  # numeric factors with more distinct values are binned into quartiles
MAX_WORST = 20
RUN_COLUMNS = {"run": int, "block": str, "seed": int, "status": str, "error": str,
               "command": str, "failure_line": int, "failure_time": float,
               "failure_mode": str, "duration": float, "simulated_time": float,
               "wall_time": float}
DETECTOR_COLUMNS = {"alarm_time": float, "isolated_line": int, "delay": float,
                    "false_alarms": int, "max_before_failure": float}
# The verdict as it evolved (campaigns from 2026-11-24 on; older ones lack them and the
# report leaves their section out).
VERDICT_COLUMNS = {"isolation_delay": float, "final_line": int,
                   "alarm_seconds_before_failure": float}
# How well each run's station keeping held (campaigns from 2026-11-25 on; older ones lack
# them and the report leaves the section out). A hull that left its setpoint heading met the
# waves from another side than the campaign set.
STATION_COLUMNS = {"heading_error_max_deg": float, "thrust_saturated_share": float}
# The sensors a detector judged faulty, "cell 6 disagrees from 482 s; GNSS jump from 930 s"
# ("" for none); a campaign written before detectors reported them has no such column.
SENSOR_COLUMN = "sensor_faults"
HEADING_LOST_DEG = 10.0  # as `moorsim batch` warns


class CampaignError(Exception):
    """campaign.h5 is missing or is not a campaign file."""


@dataclass
class Detector:
    label: str
    kind: str
    statistic: str
    threshold: float  # NaN if none
    columns: dict  # DETECTOR_COLUMNS name -> (R,) array
    grid: np.ndarray | None  # (G,) thresholds
    false_crossings: np.ndarray | None  # (R, G)
    first_crossing: np.ndarray | None  # (R, G) s


@dataclass
class Campaign:
    path: Path
    attrs: dict  # root attributes as text
    num_lines: int
    runs: dict  # column -> (R,) array
    factors: list
    detectors: list

    def __post_init__(self):
        r = self.runs
        self.size = len(r["run"])
        self.ok = r["status"] == "ok"
        self.failure = (r["failure_line"] > 0) & np.isfinite(r["failure_time"])
        self.fail_ok = self.ok & self.failure
        self.intact_ok = self.ok & (r["failure_line"] == 0)


# ---------------------------------------------------------------------------- reading


def text(value) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return text(value.item())
    return str(value)


def read_column(h5, path: str, kind, rows: int | None, ndim: int = 1) -> np.ndarray:
    where = f"{h5.filename}: {path}"
    if path not in h5 or not isinstance(h5[path], h5py.Dataset):
        raise CampaignError(f"{h5.filename}: not a campaign file: missing dataset {path}")
    dataset = h5[path]
    if dataset.ndim != ndim or (rows is not None and dataset.shape[0] != rows):
        raise CampaignError(f"{where} has shape {dataset.shape}, expected {rows} rows")
    if h5py.check_string_dtype(dataset.dtype) is not None:
        if kind is not str:
            raise CampaignError(f"{where} holds strings, expected numbers")
        return np.asarray(dataset.asstr()[()], dtype=object).astype(str)
    data = dataset[()]
    if kind is str:
        return data.astype(str)
    if data.dtype.kind not in "iuf":
        raise CampaignError(f"{where} has type {data.dtype}, expected numbers")
    if kind is int and data.dtype.kind == "f":
        raise CampaignError(f"{where} holds floats, expected integers")
    return data.astype(float) if kind is float else data


def read_campaign(path: Path) -> Campaign:
    if not path.parent.is_dir():
        raise CampaignError(f"{path.parent}: no such directory")
    if not path.is_file():
        raise CampaignError(f"{path}: no such file")
    try:
        h5 = h5py.File(path, "r")
    except OSError as error:
        raise CampaignError(f"{path}: not a readable HDF5 file ({error})") from None
    with h5:
        if not isinstance(h5.get("runs"), h5py.Group) or "num_lines" not in h5.attrs:
            raise CampaignError(f"{path}: not a campaign file (no /runs group or num_lines)")
        attrs = {key: text(value) for key, value in h5.attrs.items()}
        rows = h5["runs/run"].shape[0] if "run" in h5["runs"] else None
        runs = {name: read_column(h5, f"runs/{name}", kind, rows)
                for name, kind in RUN_COLUMNS.items()}
        if all(f"runs/{name}" in h5 for name in STATION_COLUMNS):
            runs.update({name: read_column(h5, f"runs/{name}", kind, rows)
                         for name, kind in STATION_COLUMNS.items()})
        factors = [f for f in attrs.get("factors", "").split("\n") if f]
        for factor in factors:
            dataset = h5["runs"].get(factor)
            numeric = isinstance(dataset, h5py.Dataset) and dataset.dtype.kind in "iuf"
            runs[factor] = read_column(h5, f"runs/{factor}", float if numeric else str, rows)
        detectors = []
        for label in [d for d in attrs.get("detectors", "").split("\n") if d]:
            columns = {name: read_column(h5, f"runs/{label}.{name}", kind, rows)
                       for name, kind in DETECTOR_COLUMNS.items()}
            if all(f"runs/{label}.{name}" in h5 for name in VERDICT_COLUMNS):
                columns.update({name: read_column(h5, f"runs/{label}.{name}", kind, rows)
                                for name, kind in VERDICT_COLUMNS.items()})
            if f"runs/{label}.{SENSOR_COLUMN}" in h5:
                columns[SENSOR_COLUMN] = read_column(h5, f"runs/{label}.{SENSOR_COLUMN}", str,
                                                     rows)
            group = h5.get(f"detectors/{label}")
            grid = crossings = first = None
            kind = statistic = ""
            threshold = math.nan
            if isinstance(group, h5py.Group):
                kind = text(group.attrs.get("type", ""))
                statistic = text(group.attrs.get("statistic", ""))
                try:
                    threshold = float(group.attrs.get("threshold", math.nan))
                except (TypeError, ValueError):
                    raise CampaignError(f"{path}: detectors/{label}: threshold is not a "
                                        f"number") from None
                if "thresholds" in group:
                    base = f"detectors/{label}"
                    grid = read_column(h5, f"{base}/thresholds", float, None)
                    crossings = read_column(h5, f"{base}/false_crossings", int, rows, 2)
                    first = read_column(h5, f"{base}/first_crossing", float, rows, 2)
                    if crossings.shape[1] != grid.size or first.shape[1] != grid.size:
                        raise CampaignError(f"{path}: {base}: crossing tables do not have "
                                            f"{grid.size} columns like its thresholds")
            detectors.append(Detector(label, kind, statistic, threshold, columns, grid,
                                      crossings, first))
        try:
            num_lines = int(h5.attrs["num_lines"])
        except (TypeError, ValueError):
            raise CampaignError(f"{path}: attribute num_lines is not an integer") from None
    return Campaign(path, attrs, num_lines, runs, factors, detectors)


# ---------------------------------------------------------------------------- statistics


def proportion(k: int, n: int) -> dict:
    """k of n with its Wilson (1927) score interval; numbers None when n = 0."""
    if n == 0:
        return {"k": 0, "n": 0, "rate": None, "low": None, "high": None}
    p = k / n
    interval = binomtest(int(k), int(n)).proportion_ci(CONFIDENCE, method="wilson")
    return {"k": int(k), "n": int(n), "rate": p, "low": min(p, interval.low),
            "high": max(p, interval.high)}  # min, max: rounding at p = 0 or 1


def poisson_rate(count: int, hours: float, runs: int) -> dict:
    """count events in `hours` with the exact Poisson interval (Garwood 1936):
    [chi2(a/2; 2k) / 2, chi2(1 - a/2; 2k + 2) / 2] / hours."""
    result = {"count": int(count), "hours": float(hours), "runs": int(runs), "rate": None,
              "low": None, "high": None}
    if hours > 0:
        alpha = 1 - CONFIDENCE
        low = chi2.ppf(alpha / 2, 2 * count) / 2 if count > 0 else 0.0
        result.update(rate=count / hours, low=float(low) / hours,
                      high=float(chi2.ppf(1 - alpha / 2, 2 * count + 2)) / 2 / hours)
    return result


def delay_summary(delays: np.ndarray) -> dict:
    delays = delays[np.isfinite(delays)]
    if delays.size == 0:
        return {"n": 0, "median": None, "p95": None, "max": None}
    return {"n": int(delays.size), "median": float(np.median(delays)),
            "p95": float(np.percentile(delays, 95)), "max": float(delays.max())}


def factor_levels(values: np.ndarray, mask: np.ndarray) -> list:
    """(label, run mask) per level of a factor among the runs in `mask`; numeric factors
    with more than MAX_LEVELS distinct values are cut at their quartiles."""
    if values.dtype.kind != "f":
        return [(v, mask & (values == v)) for v in sorted(set(values[mask]))]
    finite = mask & np.isfinite(values)
    levels = []
    distinct = np.unique(values[finite])
    if distinct.size <= MAX_LEVELS:
        levels = [(f"{v:g}", finite & (values == v)) for v in distinct]
    else:
        edges = np.unique(np.quantile(values[finite], [0, 0.25, 0.5, 0.75, 1]))
        index = np.searchsorted(edges[1:-1], values, side="right")
        for i in range(edges.size - 1):
            close = "]" if i == edges.size - 2 else ")"
            levels.append((f"[{edges[i]:.4g}, {edges[i + 1]:.4g}{close}", finite & (index == i)))
    if np.any(mask & ~np.isfinite(values)):
        levels.append(("none", mask & ~np.isfinite(values)))
    return levels


# ---------------------------------------------------------------------------- analysis


def analyze_detector(c: Campaign, d: Detector) -> dict:
    r, col, lines = c.runs, d.columns, c.num_lines
    detected = c.fail_ok & np.isfinite(col["alarm_time"])
    isolated = c.fail_ok & (col["isolated_line"] == r["failure_line"])

    def rates(mask):
        n = int(mask.sum())
        return {"detection": proportion(int((detected & mask).sum()), n),
                "isolation": proportion(int((isolated & mask).sum()), n),
                "delay": delay_summary(col["delay"][detected & mask])}

    per_line = {str(line): rates(c.fail_ok & (r["failure_line"] == line))
                for line in range(1, lines + 1)}
    per_factor = {f: [dict(level=label, **rates(mask))
                      for label, mask in factor_levels(r[f], c.fail_ok)] for f in c.factors}
    # Columns 1..lines: the line named at the alarm; lines + 1: no line named but a sensor
    # judged faulty; lines + 2: missed.
    sensor = np.array([bool(x) for x in col[SENSOR_COLUMN]]) if SENSOR_COLUMN in col \
        else np.zeros(c.size, dtype=bool)
    names_line = detected & (col["isolated_line"] >= 1) & (col["isolated_line"] <= lines)
    named = np.where(names_line, col["isolated_line"], np.where(sensor, lines + 1, lines + 2))
    confusion = np.zeros((lines, lines + 2), dtype=int)
    for true, seen in zip(r["failure_line"][c.fail_ok], named[c.fail_ok]):
        if 1 <= true <= lines:
            confusion[true - 1, seen - 1] += 1
    fa = col["false_alarms"]
    intact_hours = float(r["simulated_time"][c.intact_ok].sum()) / 3600
    pre_hours = float(r["failure_time"][c.fail_ok].sum()) / 3600
    result = {
        "type": d.kind, "statistic": d.statistic, "threshold": d.threshold,
        **{k: v for k, v in rates(c.fail_ok).items() if k != "delay"},
        "per_line": {k: {"detection": v["detection"], "isolation": v["isolation"]}
                     for k, v in per_line.items()},
        "per_factor": per_factor,
        "confusion": confusion.tolist(),
        "confusion_columns": [str(i) for i in range(1, lines + 1)] + ["sensor fault", "missed"],
        "alarms_without_line": int((detected & ~names_line).sum()),
        "sensor_faults_named": {"failure": proportion(int((sensor & c.fail_ok).sum()),
                                                      int(c.fail_ok.sum())),
                                "intact": proportion(int((sensor & c.intact_ok).sum()),
                                                     int(c.intact_ok.sum()))},
        "delay": dict(delay_summary(col["delay"][detected]),
                      per_line={k: v["delay"] for k, v in per_line.items()}),
        "false_alarms_per_hour": {
            "intact": poisson_rate(int(fa[c.intact_ok].sum()), intact_hours,
                                   int(c.intact_ok.sum())),
            "pre_failure": poisson_rate(int(fa[c.fail_ok].sum()), pre_hours,
                                        int(c.fail_ok.sum()))},
        "roc": None,
        "verdict": None,
    }
    if all(name in col for name in VERDICT_COLUMNS):
        # Named after the break: by an onset, a revision of a standing alarm, or an alarm
        # already standing on the line; still named at the end of the run; alarm-on time.
        named_after = c.fail_ok & np.isfinite(col["isolation_delay"])
        kept = c.fail_ok & (col["final_line"] == r["failure_line"])
        on = col["alarm_seconds_before_failure"]
        intact_seconds = float(r["simulated_time"][c.intact_ok].sum())
        pre_seconds = float(r["failure_time"][c.fail_ok].sum())
        n = int(c.fail_ok.sum())
        result["verdict"] = {
            "named_after_break": proportion(int(named_after.sum()), n),
            "naming_delay": delay_summary(col["isolation_delay"][named_after]),
            "named_at_end": proportion(int(kept.sum()), n),
            "alarm_on_share": {
                "intact": float(np.nansum(on[c.intact_ok])) / intact_seconds
                if intact_seconds > 0 else None,
                "pre_failure": float(np.nansum(on[c.fail_ok])) / pre_seconds
                if pre_seconds > 0 else None}}
    result["per_block"] = per_block(c, d)
    monitored = c.intact_ok | c.fail_ok
    hours = intact_hours + pre_hours
    if d.grid is not None and d.grid.size and hours > 0:
        crossings = d.false_crossings[monitored].sum(axis=0)
        lag = d.first_crossing[c.fail_ok] - r["failure_time"][c.fail_ok, None]
        n = max(int(c.fail_ok.sum()), 1)
        within = {f"{t:g}": ((lag <= t).sum(axis=0) / n).tolist() for t in WITHIN}
        roc = {"thresholds": d.grid.tolist(), "false_crossings": crossings.tolist(),
               "hours": hours, "runs": int(monitored.sum()),
               "false_alarms_per_hour": (crossings / hours).tolist(),
               "detected_within": within if c.fail_ok.any() else None, "configured": None}
        if math.isfinite(d.threshold):
            g = int(np.argmin(np.abs(d.grid - d.threshold)))
            roc["configured"] = {
                "threshold": d.threshold, "grid_index": g, "grid_threshold": float(d.grid[g]),
                "false_alarms_per_hour": roc["false_alarms_per_hour"][g],
                "detected_within": {t: v[g] for t, v in within.items()}
                if c.fail_ok.any() else None}
        result["roc"] = roc
    return result


def per_block(c: Campaign, d: Detector) -> dict:
    """Per block (a campaign's sea state, failure mode, ...): the verdict on its failure runs
    (named after the break, with its delay, and still named at the end; the first alarm's
    detection and isolation where the verdict columns are missing) and the false alarms
    and alarm-on share of its intact runs."""
    r, col = c.runs, d.columns
    verdict = all(name in col for name in VERDICT_COLUMNS)
    out = {}
    for b in sorted(set(r["block"])):
        in_block = r["block"] == b
        fail, intact = c.fail_ok & in_block, c.intact_ok & in_block
        n = int(fail.sum())
        entry = {"failure_runs": n, "intact_runs": int(intact.sum())}
        if n:
            entry["detection"] = proportion(int((fail & np.isfinite(col["alarm_time"])).sum()), n)
            entry["isolation"] = proportion(int((fail & (col["isolated_line"] ==
                                                         r["failure_line"])).sum()), n)
            if verdict:
                named = fail & np.isfinite(col["isolation_delay"])
                entry["named_after_break"] = proportion(int(named.sum()), n)
                entry["naming_delay"] = delay_summary(col["isolation_delay"][named])
                entry["named_at_end"] = proportion(int((fail & (col["final_line"] ==
                                                               r["failure_line"])).sum()), n)
        if intact.any():
            seconds = float(r["simulated_time"][intact].sum())
            entry["false_alarms_per_hour"] = poisson_rate(int(col["false_alarms"][intact].sum()),
                                                          seconds / 3600, int(intact.sum()))
            if verdict:
                entry["alarm_on_share"] = float(np.nansum(
                    col["alarm_seconds_before_failure"][intact])) / seconds
        out[str(b)] = entry
    return out


def truth(c: Campaign, i: int) -> str:
    line = int(c.runs["failure_line"][i])
    return f"line {line} at {c.runs['failure_time'][i]:g} s" if line > 0 else "intact"


def worst_runs(c: Campaign) -> list:
    """Up to MAX_WORST runs, taken in turn from four rankings: most detectors missing the
    failure, most naming a wrong line, largest delay, most false alarms."""
    if not c.detectors:
        return []
    labels, cols, line = [d.label for d in c.detectors], [d.columns for d in c.detectors], \
        c.runs["failure_line"]
    missed = np.array([c.fail_ok & ~np.isfinite(x["alarm_time"]) for x in cols])  # (D, R)
    wrong = np.array([c.fail_ok & np.isfinite(x["alarm_time"]) & (x["isolated_line"] != line)
                      for x in cols])
    delays = np.array([np.where(c.fail_ok & np.isfinite(x["delay"]), x["delay"], -np.inf)
                       for x in cols])
    alarms = np.array([np.where(c.ok, x["false_alarms"], 0) for x in cols])
    keys = (missed.sum(0), wrong.sum(0), delays.max(0), alarms.sum(0))
    rankings = [[i for i in np.argsort(-key, kind="stable") if key[i] > 0] for key in keys]
    chosen: dict[int, int] = {}  # run -> ranking it was taken from
    while len(chosen) < MAX_WORST and any(rankings):
        for r, ranking in enumerate(rankings):
            while ranking and ranking[0] in chosen:
                ranking.pop(0)
            if ranking and len(chosen) < MAX_WORST:
                chosen[ranking.pop(0)] = r
    entries = []
    for i, ranking in chosen.items():
        def who(mask):
            return ", ".join(l for l, m in zip(labels, mask[:, i]) if m)
        reasons = [f"{what} by {who(mask)}" for what, mask in (("missed", missed),
                                                              ("wrong line", wrong))
                   if mask[:, i].any()]
        if ranking == 2:
            reasons.append(f"delay {delays[:, i].max():.4g} s ({labels[delays[:, i].argmax()]})")
        if alarms[:, i].any():
            count = int(alarms[:, i].sum())
            reasons.append(f"{count} false alarm{'s' * (count != 1)} (" + ", ".join(
                f"{l} {k}" for l, k in zip(labels, alarms[:, i]) if k) + ")")
        entries.append({
            "run": int(c.runs["run"][i]), "seed": int(c.runs["seed"][i]),
            "block": str(c.runs["block"][i]), "truth": truth(c, i),
            "failure_line": int(c.runs["failure_line"][i]),
            "failure_time": float(c.runs["failure_time"][i]), "reasons": reasons,
            "detectors": {l: {"alarm_time": float(x["alarm_time"][i]),
                              "isolated_line": int(x["isolated_line"][i]),
                              "delay": float(x["delay"][i]),
                              "false_alarms": int(x["false_alarms"][i])}
                          for l, x in zip(labels, cols)},
            "command": str(c.runs["command"][i])})
    return entries


def station_keeping(c: Campaign) -> dict | None:
    """Per block, over its runs with status ok: how many left their setpoint heading by more
    than HEADING_LOST_DEG, and the medians of the largest heading error and of the share of
    controller updates with the thrust saturated. None for a campaign without the columns."""
    r = c.runs
    if not all(name in r for name in STATION_COLUMNS):
        return None
    out = {}
    for b in sorted(set(r["block"])):
        rows = c.ok & (r["block"] == b)
        error = r["heading_error_max_deg"][rows]
        share = r["thrust_saturated_share"][rows]
        out[b] = {"runs": int(rows.sum()),
                  "heading_lost": int((error > HEADING_LOST_DEG).sum()),
                  "heading_error_max_deg_median": float(np.median(error)) if error.size else None,
                  "thrust_saturated_share_median": float(np.median(share)) if share.size else None}
    return out


def analyze(c: Campaign) -> dict:
    r = c.runs
    statuses = {s: int((r["status"] == s).sum()) for s in sorted(set(r["status"]))}
    blocks = {b: {s: int(((r["block"] == b) & (r["status"] == s)).sum()) for s in statuses}
              for b in sorted(set(r["block"]))}
    not_ok = [{"run": int(r["run"][i]), "block": str(r["block"][i]), "seed": int(r["seed"][i]),
               "status": str(r["status"][i]), "error": str(r["error"][i]),
               "command": str(r["command"][i])} for i in np.flatnonzero(~c.ok)]
    seed = c.attrs.get("campaign_seed", "")
    return {
        "campaign": {"name": c.attrs.get("campaign_name", ""), "path": c.attrs.get(
            "campaign_path", ""), "version": c.attrs.get("version", ""),
            "command_line": c.attrs.get("command_line", ""),
            "seed": int(seed) if seed.isdigit() else seed, "num_lines": c.num_lines,
            "factors": c.factors, "detectors": [d.label for d in c.detectors],
            "confidence": CONFIDENCE},
        "runs": {"total": c.size, "status": statuses, "by_block": blocks,
                 "failure_runs_ok": int(c.fail_ok.sum()), "intact_runs_ok": int(c.intact_ok.sum()),
                 "not_ok": not_ok, "station_keeping": station_keeping(c)},
        "detectors": {d.label: analyze_detector(c, d) for d in c.detectors},
        "worst_runs": worst_runs(c),
    }


def json_safe(value):
    if isinstance(value, dict):
        return {str(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(v) for v in value]
    if isinstance(value, (np.integer, np.bool_)):
        return value.item()
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


# ---------------------------------------------------------------------------- figures


def save(figure, out_dir: Path, name: str) -> str:
    figure.savefig(out_dir / name, dpi=110)
    matplotlib.pyplot.close(figure)
    print(f"wrote {out_dir / name}")
    return name


def bars(ax, x, stats, width, j, label):
    """Bars at the rates with their intervals, and a dot so that a zero rate shows."""
    y = [s["rate"] for s in stats]
    err = [[s["rate"] - s["low"] for s in stats], [s["high"] - s["rate"] for s in stats]]
    ax.bar(x, y, width, color=f"C{j}", alpha=0.85, label=label)
    ax.errorbar(x, y, yerr=err, fmt="o", color=f"C{j}", markeredgecolor="black", markersize=4,
                ecolor="0.2", capsize=3)


def plot_rates(plt, out_dir, name, title, groups, series) -> str:
    """Detection (top) and isolation (bottom) rate per group with runs, one bar per detector
    with its interval; `series` maps a detector label to one rates dict per group."""
    first = next(iter(series.values()))
    shown = [i for i, r in enumerate(first) if r["detection"]["n"] > 0]
    figure, axes = plt.subplots(2, 1, sharex=True, layout="constrained",
                                figsize=(min(16, max(7, 1.1 * len(shown) + 3)), 6))
    width = 0.8 / max(1, len(series))
    for ax, key in zip(axes, ("detection", "isolation")):
        for j, (label, rates) in enumerate(series.items()):
            bars(ax, [k - 0.4 + width * (j + 0.5) for k in range(len(shown))],
                 [rates[i][key] for i in shown], width, j, label)
        ax.set_ylim(0, 1.05)
        ax.set_ylabel(f"{key} rate [-]")
        ax.grid(axis="y", alpha=0.3)
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize="small",
                   title="detector")
    axes[1].set_xlim(-0.5 - 0.5 / len(shown), len(shown) - 0.5 + 0.5 / len(shown))
    axes[1].set_xticks(range(len(shown)), [f"{groups[i]}\nn = {first[i]['detection']['n']}"
                                           for i in shown])
    figure.suptitle(title)
    return save(figure, out_dir, name)


def plot_confusion(plt, out_dir, c: Campaign, results: dict) -> str:
    count = len(results)
    figure, axes = plt.subplots(1, count, squeeze=False, layout="constrained",
                                figsize=(min(18, 0.55 * (c.num_lines + 2) * count + 2 * count),
                                         0.5 * c.num_lines + 2))
    for ax, (label, result) in zip(axes[0], results.items()):
        matrix = np.array(result["confusion"])
        ax.imshow(matrix, cmap="Blues", vmin=0, vmax=max(1, matrix.max()), aspect="auto")
        for (i, j), value in np.ndenumerate(matrix):
            if value:
                ax.text(j, i, str(value), ha="center", va="center", fontsize="medium",
                        color="white" if value > 0.6 * matrix.max() else "black")
        ax.set_xticks(range(len(result["confusion_columns"])), result["confusion_columns"],
                      rotation=45, ha="right")
        ax.set_yticks(range(c.num_lines), [str(i) for i in range(1, c.num_lines + 1)])
        ax.set_xlabel("line named by the detector")
        ax.set_ylabel("line that failed")
        ax.set_title(label)
    figure.suptitle("Confusion matrices: runs per (failed line, named line)")
    return save(figure, out_dir, "confusion.png")


def ecdf(ax, delays, n, end, **style):
    """Fraction of the n failure runs detected within each delay, drawn to delay `end`
    (reaches the detection rate, not 1, when some runs are missed)."""
    delays = np.sort(delays[np.isfinite(delays)])
    if delays.size:
        y = np.arange(1, delays.size + 1) / n
        ax.step(np.r_[0.0, delays, end], np.r_[0.0, y, y[-1]], where="post", **style)
    return delays.size > 0


def plot_delays(plt, out_dir, c: Campaign) -> tuple:
    r, fail_ok = c.runs, c.fail_ok
    n = int(fail_ok.sum())
    delays = np.concatenate([d.columns["delay"][fail_ok] for d in c.detectors])
    end = 1.05 * np.nanmax(delays) if np.isfinite(delays).any() else 1.0
    figure, ax = plt.subplots(layout="constrained", figsize=(7, 4.2))
    for j, d in enumerate(c.detectors):
        if not ecdf(ax, d.columns["delay"][fail_ok], n, end, color=f"C{j}", label=d.label):
            ax.plot([], [], color=f"C{j}", label=f"{d.label} (no detections)")
    ax.set(xlabel="detection delay [s]", ylabel="fraction of failure runs detected [-]",
           ylim=(0, 1.05), xlim=(0, end),
           title=f"Detection delay, failure runs with status ok (n = {n})")
    ax.grid(alpha=0.3)
    ax.legend(title="detector", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    overall = save(figure, out_dir, "delay_ecdf.png")
    lines = [line for line in range(1, c.num_lines + 1)
             if (fail_ok & (r["failure_line"] == line)).any()]
    count = len(c.detectors)
    figure, axes = plt.subplots(1, count, squeeze=False, sharey=True, layout="constrained",
                                figsize=(min(18, 4.5 * count + 1), 4))
    style = {line: {"color": f"C{(line - 1) % 10}", "linestyle": "-" if line <= 10 else "--"}
             for line in lines}
    for ax, d in zip(axes[0], c.detectors):
        drawn = [ecdf(ax, d.columns["delay"][mask], int(mask.sum()), end, **style[line])
                 for line in lines for mask in [fail_ok & (r["failure_line"] == line)]]
        if not any(drawn):
            ax.text(0.5, 0.5, "no detections", transform=ax.transAxes, ha="center", color="0.4")
        ax.set(xlabel="detection delay [s]", title=d.label, ylim=(0, 1.05), xlim=(0, end))
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("fraction of the line's failure runs [-]")
    for line in lines:
        axes[0][-1].plot([], [], label=f"line {line}", **style[line])
    if lines:
        axes[0][-1].legend(fontsize="small", title="failed line", loc="upper left",
                           bbox_to_anchor=(1.01, 1.0))
    figure.suptitle("Detection delay by failed line")
    return overall, save(figure, out_dir, "delay_ecdf_by_line.png")


def plot_false_alarms(plt, out_dir, results: dict) -> str:
    figure, ax = plt.subplots(layout="constrained", figsize=(7, 4))
    width = 0.8 / max(1, len(results))
    kinds = [("intact", "intact runs"), ("pre_failure", "failure runs before the failure")]
    for j, (label, result) in enumerate(results.items()):
        shown = [(i, result["false_alarms_per_hour"][k]) for i, (k, _) in enumerate(kinds)]
        shown = [(i, s) for i, s in shown if s["rate"] is not None]
        if shown:
            bars(ax, [i - 0.4 + width * (j + 0.5) for i, _ in shown], [s for _, s in shown],
                 width, j, label)
    ax.set_xticks(range(len(kinds)), [k[1] for k in kinds])
    ax.set(ylabel="false alarms per hour [1/h]", title="False-alarm rate (95 % exact interval)")
    ax.set_ylim(bottom=0)
    ax.grid(axis="y", alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), title="detector")
    return save(figure, out_dir, "false_alarms.png")


def plot_roc(plt, out_dir, results: dict) -> str | None:
    rocs = {label: r["roc"] for label, r in results.items()
            if r["roc"] and r["roc"]["detected_within"]}
    if not rocs:
        return None
    floor = min(0.5 / roc["hours"] for roc in rocs.values())  # where zero is drawn
    figure, axes = plt.subplots(1, len(WITHIN), sharey=True, squeeze=False, layout="constrained",
                                figsize=(14, 4.5))
    for ax, t in zip(axes[0], WITHIN):
        for j, (label, roc) in enumerate(rocs.items()):
            x = np.maximum(np.array(roc["false_alarms_per_hour"]), floor)
            ax.plot(x, roc["detected_within"][f"{t:g}"], ".-", color=f"C{j}", label=label)
            if roc["configured"]:
                g = roc["configured"]["grid_index"]
                ax.plot(x[g], roc["detected_within"][f"{t:g}"][g], "o", color=f"C{j}",
                        markersize=10, markerfacecolor="none", markeredgewidth=2)
        ax.axvline(floor, color="grey", linestyle=":", linewidth=1)
        ax.set_xscale("log")
        ax.set(xlabel="false alarms per hour [1/h]", title=f"detected within {t:g} s",
               ylim=(-0.03, 1.05))
        ax.grid(alpha=0.3, which="both")
    axes[0][0].set_ylabel("fraction of failure runs [-]")
    axes[0][0].plot([], [], "o", color="black", markerfacecolor="none",
                    label="configured threshold")
    axes[0][0].plot([], [], ":", color="grey", label=f"zero (drawn at {floor:.2g}/h)")
    axes[0][0].legend(fontsize="small")
    figure.suptitle("ROC over each detector's threshold grid (crossings counted without hold time)")
    return save(figure, out_dir, "roc.png")


# ---------------------------------------------------------------------------- HTML


class Raw(str):
    """Cell content that is already HTML."""


def cell(value) -> str:
    return value if isinstance(value, Raw) else html.escape(str(value))


def table(header: list | None, rows: list) -> str:
    head = "<tr>" + "".join(f"<th>{cell(h)}</th>" for h in header) + "</tr>" if header else ""
    body = "".join("<tr>" + "".join(f"<td>{cell(v)}</td>" for v in row) + "</tr>" for row in rows)
    return f"<table>{head}{body}</table>\n"


def number(x, digits: int = 4) -> str:
    return "–" if x is None or not math.isfinite(x) else f"{x:.{digits}g}"


def rate_text(s: dict) -> str:
    if s["n"] == 0:
        return "– (0 runs)"
    return f"{s['rate']:.3f} [{s['low']:.3f}, {s['high']:.3f}] ({s['k']}/{s['n']})"


def poisson_text(s: dict) -> str:
    if s["rate"] is None:
        return f"– ({s['runs']} runs, 0 h)"
    return (f"{s['rate']:.3g} [{s['low']:.3g}, {s['high']:.3g}] /h "
            f"({s['count']} in {s['hours']:.4g} h, {s['runs']} runs)")


def delay_text(s: dict) -> str:
    if s["n"] == 0:
        return "– (0 detected)"
    return f"{s['median']:.4g} / {s['p95']:.4g} / {s['max']:.4g} s (n = {s['n']})"


def print_summary(rep: dict) -> None:
    """The headline numbers per detector on standard output, for a terminal without a browser."""
    if not rep["detectors"]:
        return
    rows = [["detector", "detected", "isolated (the right line)", "delay median / p95 / max",
             "false alarms, intact runs"]]
    for label, r in rep["detectors"].items():
        intact = r["false_alarms_per_hour"].get("intact")
        rows.append([label, rate_text(r["detection"]), rate_text(r["isolation"]),
                     delay_text(r["delay"]), poisson_text(intact) if intact else "– (no intact run)"])
    widths = [max(len(row[i]) for row in rows) for i in range(len(rows[0]))]
    print("rates: k/n of the failure runs with a 95 % Wilson interval; the report has the rest")
    for row in rows:
        print("  ".join(cell.ljust(width) for cell, width in zip(row, widths)).rstrip())


def image(name: str | None, alt: str) -> str:
    return f'<img src="{html.escape(name)}" alt="{html.escape(alt)}">\n' if name else ""


def code(s: str) -> Raw:
    return Raw(f"<code>{html.escape(s)}</code>")


CSS = """body{font-family:sans-serif;max-width:1300px;margin:1em auto;padding:0 1em}
table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{border:1px solid #bbb;padding:2px 6px;
font-size:90%;text-align:left;vertical-align:top}th{background:#eee}img{max-width:100%}
code{font-size:85%;word-break:break-all}.note{color:#444;font-size:92%}"""


@dataclass
class Page:
    plt: object  # matplotlib.pyplot
    out_dir: Path
    c: Campaign
    rep: dict  # the report's numbers, as in report.json

    def __post_init__(self):
        self.results = self.rep["detectors"]
        self.labels = list(self.results)
        self.n_fail = self.rep["runs"]["failure_runs_ok"]
        self.fail_note = f"failure runs with status ok (n = {self.n_fail})"
        self.lines = [str(i) for i in range(1, self.c.num_lines + 1)]


def header_section(p: Page) -> list:
    camp, name = p.rep["campaign"], html.escape(p.rep["campaign"]["name"])
    out = [f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>Campaign report: {name}"
           f"</title><style>{CSS}</style></head><body><h1>Campaign report: {name}</h1>",
           table(None, [["campaign", camp["name"]], ["campaign file", camp["path"]],
                        ["moorsim version", camp["version"]],
                        ["command line", code(camp["command_line"])],
                        ["runs", p.rep["runs"]["total"]], ["campaign seed", camp["seed"]],
                        ["mooring lines", camp["num_lines"]],
                        ["factors", ", ".join(camp["factors"]) or "none"],
                        ["detectors", ", ".join(p.labels) or "none"]]),
           "<p class='note'>All intervals are 95 %: Wilson (1927) score intervals for "
           "proportions, exact Poisson intervals (Garwood 1936) for false-alarm rates. A failure "
           "run is detected when its detector alarms at or after the failure time, and isolated "
           "when the line it names is the one that failed. Runs whose status is not ok are left "
           "out of every statistic but the counts.</p>",
           f"<details><summary>campaign file text</summary><pre>"
           f"{html.escape(p.c.attrs.get('campaign', ''))}</pre></details>"]
    if p.labels:
        out.append(table(["detector", "type", "statistic", "threshold"],
                         [[l, r["type"], r["statistic"], number(r["threshold"])]
                          for l, r in p.results.items()]))
    return out


def runs_section(p: Page) -> list:
    runs = p.rep["runs"]
    statuses = list(runs["status"])
    out = [f"<h2>Runs</h2><p class='note'>All {runs['total']} runs, by block and status; "
           f"{p.n_fail} failure runs and {runs['intact_runs_ok']} intact runs have status ok."
           f"</p>", table(["block"] + statuses,
                          [[b] + [v[s] for s in statuses] for b, v in runs["by_block"].items()]
                          + [["all"] + [runs["status"][s] for s in statuses]])]
    kept = runs.get("station_keeping")
    if kept:
        lost = sum(v["heading_lost"] for v in kept.values())
        warning = (f" <b>{lost} runs left their setpoint heading by more than "
                   f"{HEADING_LOST_DEG:g} deg: they met the waves from another side than their "
                   f"factors say.</b>" if lost else "")
        out += [f"<h3>Station keeping</h3><p class='note'>Runs with status ok, by block: how "
                f"many left their setpoint heading by more than {HEADING_LOST_DEG:g} deg, the "
                f"median of the largest heading error, and the median share of controller "
                f"updates whose thrust the allocation scaled down.{warning}</p>",
                table(["block", "runs", "heading lost", "heading error max, median [deg]",
                       "thrust saturated, median share"],
                      [[b, v["runs"], v["heading_lost"],
                        "" if v["heading_error_max_deg_median"] is None
                        else f"{v['heading_error_max_deg_median']:.1f}",
                        "" if v["thrust_saturated_share_median"] is None
                        else f"{v['thrust_saturated_share_median']:.2f}"]
                       for b, v in kept.items()])]
    if runs["not_ok"]:
        out += ["<h3>Runs that did not finish</h3>",
                table(["run", "block", "seed", "status", "error", "command"],
                      [[x["run"], x["block"], x["seed"], x["status"], x["error"],
                        code(x["command"])] for x in runs["not_ok"]])]
    return out


def rates_section(p: Page) -> list:
    out = [f"<h2>Detection and isolation</h2><p class='note'>From {p.fail_note}. Cells: rate "
           f"[95 % interval] (k/n).</p>"]
    groups = ["all"] + [f"line {i}" for i in p.lines]
    series = {l: [r] + [r["per_line"][i] for i in p.lines] for l, r in p.results.items()}
    kinds = ("detection", "isolation")
    if p.n_fail:
        out.append(image(plot_rates(p.plt, p.out_dir, "rates_by_line.png",
                                    f"Detection and isolation by failed line\n{p.fail_note}",
                                    groups, series), "rates by line"))
    out.append(table(["failed line"] + [f"{l} {k}" for l in p.labels for k in kinds],
                     [[g] + [rate_text(series[l][i][k]) for l in p.labels for k in kinds]
                      for i, g in enumerate(groups)]))
    columns = (("detection", rate_text), ("isolation", rate_text), ("delay", delay_text))
    for number_, factor in enumerate(p.c.factors, start=1):
        levels = {l: r["per_factor"][factor] for l, r in p.results.items()}
        first = levels[p.labels[0]]
        out.append(f"<h3>By factor <code>{html.escape(factor)}</code></h3>")
        if first and p.n_fail:
            slug = re.sub(r"[^A-Za-z0-9_.-]+", "_", factor)
            out.append(image(plot_rates(p.plt, p.out_dir, f"rates_by_factor{number_}_{slug}.png",
                                        f"Detection and isolation by {factor}\n{p.fail_note}",
                                        [x["level"] for x in first], levels), factor))
        out.append(table(["level", "runs"] + [f"{l} {k}" for l in p.labels for k in
                                              (*kinds, "delay median / p95 / max")],
                         [[x["level"], x["detection"]["n"]] +
                          [f(levels[l][i][k]) for l in p.labels for k, f in columns]
                          for i, x in enumerate(first)]))
    return out


def confusion_section(p: Page) -> list:
    out = [f"<h2>Confusion matrices</h2><p class='note'>From {p.fail_note}: rows the line that "
           f"failed, columns the line the detector named at its alarm; <i>sensor fault</i>: no "
           f"line named, a sensor judged faulty; <i>missed</i>: neither (no alarm at or after "
           f"the failure, or an alarm naming no line).</p>"]
    if p.n_fail:
        out.append(image(plot_confusion(p.plt, p.out_dir, p.c, p.results), "confusion matrices"))
    for l, r in p.results.items():
        extra = (f" ({r['alarms_without_line']} alarms named no line)"
                 if r["alarms_without_line"] else "")
        intact = r["sensor_faults_named"]["intact"]
        if intact["k"]:
            extra += (f"; on intact runs it judged a sensor faulty in {intact['k']} of "
                      f"{intact['n']}")
        out += [f"<h4>{html.escape(l + extra)}</h4>",
                table(["failed line \\ named"] + r["confusion_columns"],
                      [[i + 1] + row for i, row in enumerate(r["confusion"])])]
    return out


def delay_section(p: Page) -> list:
    out = [f"<h2>Detection delay</h2><p class='note'>Delay = alarm time − failure time, over the "
           f"detected runs among the {p.fail_note}. The curves give the fraction of all those "
           f"runs detected within a delay, so each levels off at the detection rate. Percentiles "
           f"interpolate linearly between order statistics.</p>"]
    if p.n_fail:
        overall, by_line = plot_delays(p.plt, p.out_dir, p.c)
        out.append(image(overall, "delay ECDF") + image(by_line, "delay ECDF by line"))
    delays = {l: r["delay"] for l, r in p.results.items()}
    out.append(table(["failed line"] + [f"{l} median / p95 / max" for l in p.labels],
                     [["all"] + [delay_text(delays[l]) for l in p.labels]] +
                     [[i] + [delay_text(delays[l]["per_line"][i]) for l in p.labels]
                      for i in p.lines]))
    return out


def false_alarm_section(p: Page) -> list:
    out = [f"<h2>False alarms per hour</h2><p class='note'>Alarm onsets of the detector as "
           f"configured (with its hold time) per hour: on intact runs with status ok (n = "
           f"{p.rep['runs']['intact_runs_ok']}) over their simulated time, and on the "
           f"{p.fail_note} before the failure, over the time up to the failure.</p>"]
    rates = {l: r["false_alarms_per_hour"] for l, r in p.results.items()}
    if any(x["rate"] is not None for r in rates.values() for x in r.values()):
        out.append(image(plot_false_alarms(p.plt, p.out_dir, p.results), "false alarms"))
    out.append(table(["detector", "intact runs", "failure runs before the failure"],
                     [[l, poisson_text(r["intact"]), poisson_text(r["pre_failure"])]
                      for l, r in rates.items()]))
    return out


def verdict_section(p: Page) -> list:
    verdicts = {l: r["verdict"] for l, r in p.results.items() if r.get("verdict")}
    if not verdicts:
        return []

    def share(x):
        return "-" if x is None else f"{100 * x:.2f} %"

    out = [f"<h2>The verdict over time</h2><p class='note'>From {p.fail_note}. Named after the "
           f"break: the verdict named the failed line at some time after the failure, by an "
           f"alarm onset, by revising an alarm that already stood, or because an alarm on it "
           f"already stood (the first-onset columns above miss the last two). Still named at "
           f"the end: the run ended with the alarm on, naming the failed line. Alarm on: the "
           f"share of the time an alarm stood, on intact runs and before the failure.</p>"]
    out.append(table(["detector", "named after the break", "delay median / p95 / max",
                      "still named at the end", "alarm on, intact", "alarm on, before failure"],
                     [[l, rate_text(v["named_after_break"]), delay_text(v["naming_delay"]),
                       rate_text(v["named_at_end"]), share(v["alarm_on_share"]["intact"]),
                       share(v["alarm_on_share"]["pre_failure"])] for l, v in verdicts.items()]))
    return out


def block_section(p: Page) -> list:
    blocks = sorted({b for r in p.results.values() for b in r.get("per_block", {})})
    if len(blocks) < 2:
        return []
    out = ["<h2>By block</h2><p class='note'>Each block of the campaign (a sea state, a "
           "failure mode, ...) on its own. Failure runs: the verdict named the failed line "
           "after the break (delay median / p95), and still named it at the end (first-alarm "
           "isolation where the campaign predates the verdict columns). Intact runs: false "
           "alarms per hour (onsets) and the share of the time an alarm stood.</p>"]
    rows = []
    for label, result in p.results.items():
        for b in blocks:
            e = result.get("per_block", {}).get(b)
            if e is None:
                continue
            named = e.get("named_after_break", e.get("isolation"))
            on = e.get("alarm_on_share")
            rows.append([label, b, rate_text(named) if named else "-",
                         delay_text(e["naming_delay"]) if "naming_delay" in e else "-",
                         rate_text(e["named_at_end"]) if "named_at_end" in e else "-",
                         poisson_text(e["false_alarms_per_hour"])
                         if "false_alarms_per_hour" in e else "-",
                         "-" if on is None else f"{100 * on:.2f} %"])
    out.append(table(["detector", "block", "named after the break", "delay median / p95 / max",
                      "still named at the end", "false alarms per intact hour", "alarm on"],
                     rows))
    return out


def roc_section(p: Page) -> list:
    out = ["<h2>ROC</h2><p class='note'>For each threshold of a detector's grid: false alarms "
           "per hour = upcrossings of the threshold by the statistic (without the hold time) on "
           "intact runs and on failure runs before the failure, all with status ok, over their "
           f"monitored hours; detected = fraction of the {p.fail_note} whose statistic reaches "
           "the threshold within 60, 120 or 300 s after the failure. The ring marks the grid "
           "threshold nearest the configured one.</p>",
           image(plot_roc(p.plt, p.out_dir, p.results), "ROC curves")]
    for l, r in p.results.items():
        roc = r["roc"]
        if roc is None:
            out.append(f"<p>{html.escape(l)}: no threshold grid or no monitored time.</p>")
            continue
        conf, within = roc["configured"], roc["detected_within"] or {}
        summary = "no configured threshold" if conf is None else (
            f"configured threshold {number(conf['threshold'])}, nearest grid point "
            f"{number(conf['grid_threshold'])}: {number(conf['false_alarms_per_hour'], 3)} "
            f"false alarms per hour")
        rows = zip(roc["thresholds"], roc["false_crossings"], roc["false_alarms_per_hour"])
        out += [f"<details><summary>{html.escape(l)}: {len(roc['thresholds'])} thresholds, "
                f"{roc['runs']} runs, {roc['hours']:.4g} monitored hours; "
                f"{html.escape(summary)}</summary>",
                table(["threshold", "false crossings", "false alarms per hour"] +
                      [f"detected within {t} s" for t in within],
                      [[number(g), k, number(x, 3)] + [number(v[i], 3) for v in within.values()]
                       for i, (g, k, x) in enumerate(rows)]), "</details>"]
    return out


def worst_section(p: Page) -> list:
    def did(x):
        alarm = (f"line {x['isolated_line']} at {number(x['alarm_time'])} s"
                 if x["alarm_time"] is not None else "no alarm")
        delay = f", delay {number(x['delay'])} s" if x["delay"] is not None else ""
        count = x["false_alarms"]
        return f"{alarm}{delay}, {count} false alarm{'s' * (count != 1)}"

    return [f"<h2>Worst runs</h2><p class='note'>Up to {MAX_WORST} runs with status ok, taken "
            f"in turn from: most detectors missing the failure, most naming a wrong line, "
            f"largest delay, most false alarms. Per detector: line named at the alarm (the "
            f"first alarm for intact runs), delay, false alarms.</p>",
            table(["run", "seed", "block", "truth", "why"] + p.labels + ["command"],
                  [[w["run"], w["seed"], w["block"], w["truth"], "; ".join(w["reasons"])]
                   + [did(w["detectors"][l]) for l in p.labels] + [code(w["command"])]
                   for w in p.rep["worst_runs"]])]


def interval_text(e: dict | None) -> str:
    if not e:
        return "–"
    return f"{number(e['value'])} [{number(e['lower'])}, {number(e['upper'])}]"


def result_text(passed) -> str:
    return "–" if passed is None else ("pass" if passed else "FAIL")


def design_section(p: Page) -> list:
    """The campaign's design checks (DIR/design.json, written by `moorsim batch`)."""
    d = p.rep.get("design")
    if not d:
        return []
    standard = {"api_rp_2sk": "API RP 2SK (the MPM against the breaking load)",
                "dnv_os_e301": f"DNV-OS-E301, consequence class {d['consequence_class']} "
                               "(partial factors on mean and dynamic tension against 0.95 MBL)"}
    out = [f"<h2>Design checks</h2><p class='note'>By {html.escape(standard[d['standard']])}. "
           f"MPM (method gumbel): the mode of a Gumbel distribution fitted by maximum "
           f"likelihood to the storms' (seeds') maxima; (method weibull): the value exceeded "
           f"once in a {d.get('storm_duration', 10800):g} s storm by the peaks of one long "
           f"run, Weibull-fitted; with its {d['confidence']:.0%} interval; the "
           f"{d['quantile']:g} quantile beside it. Tensions in kN. Each entry's runs are in "
           f"design.json (run_indices); each run's row holds the command that repeats it. "
           f"The tables are also design.csv and fatigue.csv.</p>"]
    rows = []
    for e in d["extremes"]:
        check = e.get("check") or {}
        kn = lambda x: None if x is None else x / 1e3
        rows.append([e["block"], e["point"], e["condition"], e.get("parted_line", "–"), e["line"],
                     e["type"], e["runs"], e.get("method", "gumbel"),
                     interval_text({k: kn(v) for k, v in e["mpm"].items()} if e.get("mpm") else None),
                     number(kn((e.get("quantile") or {}).get("value"))),
                     number(kn(e.get("mean_tension"))), number(kn(e.get("minimum_breaking_load"))),
                     number(kn(check.get("design_tension"))),
                     f"{number(check.get('safety_factor'), 3)} ({number(check.get('required_factor'), 3)})",
                     number(check.get("utilisation"), 3), result_text(check.get("pass")),
                     e.get("runs_for_5_percent", "–"), e.get("note", "")])
    out.append(table(["block", "point", "condition", "parted line", "line", "type", "runs",
                      "method", "MPM [interval]", "quantile", "mean", "MBL", "design tension",
                      "safety factor (required)", "utilisation", "result",
                      "seeds for ±5 %", "note"], rows))
    out.append("<p class='note'>The vessel's largest offset from its initial pose [m].</p>")
    out.append(table(["block", "point", "condition", "runs", "MPM [interval]", "limit", "result"],
                     [[o["block"], o["point"], o["condition"], o["runs"],
                       interval_text(o.get("mpm")), number(o.get("limit")),
                       result_text(o.get("pass"))] for o in d["offsets"]]))
    f = d["fatigue"]
    if f["states"]:
        out.append(f"<p class='note'>Fatigue over {len(f['states'])} sea states (their "
                   f"probabilities sum to {f['probability']:.4g}): damage per year and life, "
                   f"against a service life of {f['service_life']:g} years times "
                   f"{f['fatigue_factor']:g}.</p>")
        out.append(table(["line", "place", "type", "damage per year", "life [years]", "result",
                          "note"],
                         [[line["line"], place, line[place]["type"],
                           number(line[place]["annual_damage"], 3),
                           number(line[place]["life_years"], 4), result_text(line[place]["pass"]),
                           line[place].get("note", "")]
                          for line in f["lines"] for place in ("top", "touchdown")]))
    return out


def write_html(p: Page) -> None:
    out = header_section(p) + runs_section(p) + design_section(p)
    if not p.labels:
        out.append("<p>The campaign has no detectors: nothing more to report.</p>")
    for section in (rates_section, confusion_section, delay_section, verdict_section,
                    block_section, false_alarm_section, roc_section,
                    worst_section) if p.labels else ():
        out += section(p)
    out.append("</body></html>\n")
    (p.out_dir / "report.html").write_text("".join(out), encoding="utf-8")
    print(f"wrote {p.out_dir / 'report.html'}")


# ---------------------------------------------------------------------------- main


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        description="Report a moorsim campaign (DIR/campaign.h5) as HTML, PNGs and JSON.")
    parser.add_argument("dir", type=Path, metavar="DIR", help="directory holding campaign.h5")
    parser.add_argument("--out", type=Path, metavar="DIR2", help="where to write (default DIR)")
    return parser.parse_args(argv)


def main(argv: list[str]) -> int:
    args = parse_arguments(argv)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # after choosing the backend

    try:
        campaign = read_campaign(args.dir / "campaign.h5")
    except CampaignError as error:
        print(f"report: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    out_dir = args.out if args.out is not None else args.dir
    out_dir.mkdir(parents=True, exist_ok=True)
    rep = analyze(campaign)
    design = args.dir / "design.json"
    if design.exists():
        with open(design, encoding="utf-8") as stream:
            rep["design"] = json.load(stream)
    rep = json_safe(rep)
    with open(out_dir / "report.json", "w", encoding="utf-8") as stream:
        json.dump(rep, stream, indent=1, allow_nan=False)
    print(f"wrote {out_dir / 'report.json'}")
    plt.rcParams.update({"figure.max_open_warning": 0})
    write_html(Page(plt, out_dir, campaign, rep))
    print_summary(rep)
    plt.close("all")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
