#!/usr/bin/python3
"""What any detector can at best do against a sea state's slowly varying load: reads the
intact runs of a campaign kept with `moorsim batch --keep-runs`, estimates the disturbance a
parted line's lost load has to be seen through, and prints, per sea state (campaign block)
and per line, the least detection delay a detector can reach at a given false-alarm rate.

    tools/attainable.py DIR --static STATIC.json [--rate R]... [--share A]... [--lag S]
                        [--skip S] [--target S] [--off-bow DEG] [--json OUT.json]
    tools/attainable.py DIR --explain [--skip S] [--json OUT.json]

DIR is the campaign's results directory (DIR/rows/*.json, DIR/runs/*/run.h5); STATIC.json is
`moorsim static SCENARIO --json` for the campaign's mooring (each line's horizontal tension).
Only intact runs are read (a failure run's load changes at its break). Per block it prints
where each run's mean wave drift comes from relative to the bow: the disturbance depends on
it far more than on anything else (a hull that has lost its heading takes the waves on the
beam), and `--off-bow` keeps only the runs within an angle of it.

Two disturbances, both the horizontal force in hull axes after `--skip` seconds:
  drift  the slowly varying wave drift on the hull (/environment/waves_drift): what the sea
         itself puts in the way, seen by nobody; a detector that saw the true force on the
         hull, with the drift its only disturbance, would face this;
  bias   the intact filter's load estimate (/observer/bias, turned into hull axes by the
         heading), what the force-deficit test reads: the drift plus current and wind
         variation, the filter's estimation error and its model error.

Bound. Everything is in hull axes (surge, sway), where the disturbance keeps its shape as
the heading changes; each run's lines enter at their bearings from the hull. A parted line k
takes a share a of its horizontal load d_k (the tension towards its
anchor) off the vessel for good. Seen through a stationary Gaussian disturbance that is
averaged over a delay long against its correlation time, the evidence for that step grows
at the Kullback-Leibler rate
    I_k = a^2 d_k^T S^-1 d_k / 2   [nats/s],
S the disturbance's long-run covariance (the sum of its autocovariances over all lags, the
spectral density at zero frequency; estimated per run by Bartlett's lag window of `--lag`
seconds, pooled over the runs of a block). The log-likelihood ratio is then a Brownian
motion with drift +-I and variance rate 2I, for which Page's CUSUM is exactly optimal in
Lorden's (1971) minimax sense (Shiryaev 1996; Beibel 1996): at a mean time between false
alarms gamma = 1 / rate its threshold h solves e^h - h - 1 = gamma I, and its worst-case
mean delay is (h + e^-h - 1) / I (Basseville & Nikiforov 1993, section 5.2). The median
delay printed is that of the first passage of the drift +I to h (an inverse Gaussian law,
the reflection at 0 neglected; slightly below the mean). No detector reading that
disturbance reaches a lower mean delay at that false-alarm rate.

What the bound leaves out: a detector may use more than the averaged load. A break is
abrupt, a drift group builds up over tens of seconds, so right after the break the vessel's
acceleration carries evidence the average does not; the filter's bias lags the break by its
20-30 s time constant and so holds little of it. The "drift" rows are therefore not a bound
on every conceivable detector, but on those that judge a load averaged over their delay. The
"bias" rows bound every test on the filter's load estimate once the estimate has moved: as
the bias approaches the step like a first-order lag of time constant T, the evidence it
gathers by time t is about I (t - 1.5 T), so such a test needs about 1.5 T more. The
disturbance is not Gaussian either (drift groups are bursts): its tails raise the false
alarms of a Gaussian-tuned threshold, so real detectors sit above the bound.

How much of the disturbance a drift model could remove (`--explain`): per intact run, the
share of the variance of the bias's 15 s mean (Earth axes, as the force-deficit test reads
it) that a linear regression explains out of sample (fitted on the first half of the run
after `--skip`, judged on the second half) on
  drift           the true wave drift (Earth axes) through a 15 s first-order lag, as the
                  filter lags: what a perfect drift model could explain;
  filter, energy  the 15 s mean of x^2 + y^2 of the filter's wave-frequency motion
                  (/observer/wave_motion): the deficit test's drift regression;
  filter, direction  the 15 s means of x^2, y^2 and xy (`drift_direction`);
  true, energy / direction  the same of the true wave-frequency motion (/vessel/pose_true
                  less /vessel/pose_low_frequency): what the pose would tell without sensor
                  noise.
Printed per block as the median and range over its runs, with the bias's standard deviation
and what is left of it after the true drift.

A missing directory, file or dataset ends the script with one line naming it and exit 2.
Needs Debian's python3-numpy and python3-h5py (tools/setup.sh); use /usr/bin/python3.
"""

import argparse
import json
import math
import statistics
import sys
from pathlib import Path

try:
    import h5py
    import numpy as np
except ImportError as error:
    print(f"attainable: python module '{error.name}' is missing: install python3-numpy "
          f"python3-h5py (tools/setup.sh) and use /usr/bin/python3", file=sys.stderr)
    sys.exit(1)

EXIT_BAD_INPUT = 2
HOUR = 3600.0


class InputError(Exception):
    """A file or dataset the analysis needs is missing or malformed."""


def long_run_covariance(x, lag):
    """Bartlett's (Newey & West 1987) estimate of the long-run covariance of the rows of x
    (n samples x p channels, one sample per unit time) about their mean, lag window `lag`
    samples: Gamma_0 + sum_{l=1..lag} (1 - l / (lag + 1)) (Gamma_l + Gamma_l^T)."""
    x = np.asarray(x, dtype=float)
    x = x - x.mean(axis=0)
    n = x.shape[0]
    if n <= lag + 1:
        raise ValueError(f"{n} samples are too few for a {lag}-sample lag window")
    total = x.T @ x / n
    for l in range(1, lag + 1):
        gamma = x[l:].T @ x[:-l] / n
        total += (1.0 - l / (lag + 1.0)) * (gamma + gamma.T)
    return total


def cusum_threshold(gamma_information):
    """h > 0 with e^h - h - 1 = gamma * I (the Brownian CUSUM's mean time to a false alarm
    is (e^h - h - 1) / I)."""
    g = float(gamma_information)
    if not g > 0.0:
        raise ValueError(f"gamma * I must be positive, got {g}")
    # Start near the root (e^h - h - 1 ~ h^2 / 2 for small h, ~ e^h for large); Newton's
    # steps on this convex, increasing function converge from either side.
    h = math.sqrt(2.0 * g) if g < 1.0 else math.log(g) + 1.0
    for _ in range(100):
        f = math.expm1(h) - h - g
        step = f / math.expm1(h)
        h -= step
        if abs(step) < 1e-13 * max(1.0, h):
            break
    return h


def cusum_mean_delay(h, information):
    """Mean time of the Brownian CUSUM, started at 0, to reach h under the change."""
    return (h + math.exp(-h) - 1.0) / information


def first_passage_median(h, information):
    """Median time for a Brownian motion with drift I and variance rate 2 I, started at 0,
    to reach h: the inverse Gaussian law with mean h / I and shape h^2 / (2 I)."""
    mean = h / information
    shape = h * h / (2.0 * information)
    normal = statistics.NormalDist()

    def cdf(t):
        root = math.sqrt(shape / t)
        tail = normal.cdf(-root * (t / mean + 1.0))
        return normal.cdf(root * (t / mean - 1.0)) + (math.exp(2.0 * shape / mean) * tail
                                                      if tail > 0.0 else 0.0)

    low, high = 1e-9 * mean, mean
    while cdf(high) < 0.5:
        high *= 2.0
    for _ in range(200):
        middle = 0.5 * (low + high)
        low, high = (middle, high) if cdf(middle) < 0.5 else (low, middle)
    return 0.5 * (low + high)


def bound(information, rate_per_hour):
    """(h, mean delay, median delay) of the optimal detector at this false-alarm rate."""
    gamma = HOUR / rate_per_hour
    h = cusum_threshold(gamma * information)
    return h, cusum_mean_delay(h, information), first_passage_median(h, information)


def read_dataset(path, file, name):
    if name not in file:
        raise InputError(f"{path}: no dataset {name}")
    return np.asarray(file[name][...], dtype=float)


def read_run_datasets(path, names, skip, least):
    """The time step, the mask of the samples at or after `skip` s (at least `least` of them,
    evenly spaced) and the named datasets whole."""
    try:
        file = h5py.File(path, "r")
    except OSError as error:
        raise InputError(f"{path}: not an HDF5 file ({error})") from None
    with file:
        time = read_dataset(path, file, "/time")
        keep = time >= skip
        if keep.sum() < least:
            raise InputError(f"{path}: fewer than {least} samples after {skip} s")
        steps = np.diff(time[keep])
        if not np.allclose(steps, steps[0], rtol=1e-6):
            raise InputError(f"{path}: /time is not evenly spaced")
        data = {name: read_dataset(path, file, name) for name in names}
    if "/observer/bias" in data and not np.all(np.isfinite(data["/observer/bias"][keep, :2])):
        raise InputError(f"{path}: /observer/bias has NaN after {skip} s")
    return float(steps[0]), keep, data


def rotate(xy, angle):
    """The rows (x, y) turned by `angle` [rad] per row: hull to Earth axes by the heading,
    Earth to hull by minus it."""
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack((c * xy[:, 0] - s * xy[:, 1], s * xy[:, 0] + c * xy[:, 1]))


def read_run(path, skip):
    """The run's time step, its two horizontal disturbances in hull axes (surge, sway) after
    `skip` s, its mean heading and position, and its anchors."""
    dt, keep, data = read_run_datasets(path, (
        "/vessel/pose_low_frequency", "/environment/waves_drift", "/observer/bias",
        "/mooring/anchors"), skip, 100)
    pose = data["/vessel/pose_low_frequency"][keep]
    drift = data["/environment/waves_drift"][keep][:, :2]
    psi = pose[:, 5]
    bias = rotate(data["/observer/bias"][keep], -psi)
    anchors = data["/mooring/anchors"]
    c, s = np.cos(psi), np.sin(psi)
    heading = math.atan2(s.mean(), c.mean())
    # Where the mean wave drift comes from relative to the bow (it pushes down-wave, though
    # not exactly along the waves: a hull's sway drift grows faster off the bow than its
    # surge drift): 0 = from ahead, +90 deg = from starboard.
    drift_from = math.degrees(math.atan2(-drift[:, 1].mean(), -drift[:, 0].mean()))
    return {"dt": dt, "drift": drift, "bias": bias, "heading": heading,
            "drift_from": drift_from,
            "position": pose[:, :2].mean(axis=0), "anchors": anchors[:, :2]}


def read_line_loads(path):
    try:
        static = json.loads(Path(path).read_text())
        return {int(line["id"]): float(line["horizontal_tension"]) for line in static["lines"]
                if not line.get("broken", False)}
    except (OSError, ValueError, KeyError, TypeError) as error:
        raise InputError(f"{path}: not the output of `moorsim static --json` ({error})") \
            from None


def intact_runs_by_block(directory):
    rows = sorted((directory / "rows").glob("*.json"))
    if not rows:
        raise InputError(f"{directory / 'rows'}: no finished runs (is this a campaign's "
                         f"results directory?)")
    blocks = {}
    for row_path in rows:
        row = json.loads(row_path.read_text())
        # A failure run's row carries {"failure": {"line": k, ...}}, an intact run's null.
        if row.get("status") != "ok" or (row.get("failure") or {}).get("line", 0):
            continue
        run = directory / "runs" / row_path.stem / "run.h5"
        if not run.exists():
            raise InputError(f"{run}: missing (run the campaign with --keep-runs)")
        blocks.setdefault(row.get("block", ""), []).append(run)
    if not blocks:
        raise InputError(f"{directory}: no intact runs that finished")
    return blocks


def analyze(directory, line_loads, rates, shares, lag_seconds, skip, target, off_bow):
    result = []
    for block, runs in intact_runs_by_block(directory).items():
        data = [read_run(run, skip) for run in runs]
        drift_from = [d["drift_from"] for d in data]
        if off_bow is not None:
            data = [d for d in data if abs(d["drift_from"]) <= off_bow]
            if not data:
                continue
        dt = data[0]["dt"]
        lag = int(round(lag_seconds / dt))
        entry = {"block": block, "runs": len(data), "drift_from": drift_from,
                 "hours": sum(len(d["bias"]) for d in data) * dt / HOUR, "sources": {}}
        # Each run's lines in hull axes: the disturbance's shape follows the hull (a vessel
        # into the weather takes its drift mostly in surge), the lines' bearings to it vary.
        loads = []
        for d in data:
            for k, load in sorted(line_loads.items()):
                towards = d["anchors"][k - 1] - d["position"]
                bearing = math.atan2(towards[1], towards[0]) - d["heading"]
                loads.append(load * np.array([math.cos(bearing), math.sin(bearing)]))
        for source in ("drift", "bias"):
            weights = [len(d[source]) for d in data]
            # Per run about its own mean (a detector learns each run's baseline); samples ->
            # seconds: S [N^2 s] = dt * sum of the per-sample autocovariances.
            long_run = dt * sum(w * long_run_covariance(d[source], lag)
                                for w, d in zip(weights, data)) / sum(weights)
            variance = sum(w * np.cov(d[source].T) for w, d in zip(weights, data)) / sum(weights)
            inverse = np.linalg.inv(long_run)
            bounds = []
            for share in shares:
                for rate in rates:
                    delays = []
                    for d in loads:
                        information = 0.5 * share * share * float(d @ inverse @ d)
                        delays.append(bound(information, rate) + (information,))
                    medians = sorted(b[2] for b in delays)
                    worst = max(delays, key=lambda b: b[1])
                    bounds.append({
                        "share": share, "rate_per_hour": rate,
                        "median_delay": {"least": medians[0],
                                         "median": statistics.median(medians),
                                         "most": medians[-1]},
                        "worst": {"information": worst[3], "threshold": worst[0],
                                  "mean_delay": worst[1], "median_delay": worst[2]},
                        "share_above_target": sum(m > target for m in medians) / len(medians)})
            entry["sources"][source] = {
                "std": np.sqrt(np.diag(variance)).tolist(),
                # Integral time scale per axis: S_ii / (2 var_ii), the time constant of an
                # exponential autocorrelation with this long-run variance.
                "time_scale": (np.diag(long_run) / (2.0 * np.diag(variance))).tolist(),
                "long_run_covariance": long_run.tolist(), "bounds": bounds}
        result.append(entry)
    return result


def print_table(result, target):
    print(f"least median delay [s] of any detector averaging the load, over every run's "
          f"lines; 'above' = share of the breaks whose bound exceeds {target:g} s")
    for entry in result:
        print(f"\n{entry['block']}: {entry['runs']} intact runs, {entry['hours']:.1f} h; mean drift "
              f"from (deg off the bow, all runs): "
              f"{' '.join(f'{a:.0f}' for a in sorted(entry['drift_from'], key=abs))}")
        for source, values in entry["sources"].items():
            std, scale = values["std"], values["time_scale"]
            print(f"  {source}: std surge {std[0] / 1e6:.2f} / sway {std[1] / 1e6:.2f} MN, "
                  f"integral time scale {scale[0]:.0f} / {scale[1]:.0f} s")
            for b in values["bounds"]:
                m, w = b["median_delay"], b["worst"]
                print(f"    share {b['share']:g}, {b['rate_per_hour']:g} false alarms/h: "
                      f"{m['least']:.0f} / {m['median']:.0f} / {m['most']:.0f} s "
                      f"(least / median / most), above {100 * b['share_above_target']:.0f} %; "
                      f"worst {w['information']:.3f} nats/s, mean delay {w['mean_delay']:.0f} s")


EXPLAIN_WINDOW = 15  # [samples] the deficit test's window
EXPLAIN_LAG = 15.0   # [s] the filter's lag behind the true drift


def trailing_mean(x, window):
    """The mean of the last `window` rows at every row (fewer at the start)."""
    cumulative = np.cumsum(np.vstack((np.zeros((1, x.shape[1])), x)), axis=0)
    index = np.arange(1, len(x) + 1)
    start = np.maximum(index - window, 0)
    return (cumulative[index] - cumulative[start]) / (index - start)[:, None]


def first_order_lag(x, time_constant, dt):
    y = np.empty_like(x)
    y[0] = x[0]
    a = dt / (time_constant + dt)
    for i in range(1, len(x)):
        y[i] = y[i - 1] + a * (x[i] - y[i - 1])
    return y


def explained_out_of_sample(target, features):
    """1 - residual variance / variance of `target` on the second half, the linear regression
    (with intercept) of target on features fitted on the first half."""
    n = len(target)
    half = n // 2
    design = np.column_stack((np.ones(n), features))
    coefficients, *_ = np.linalg.lstsq(design[:half], target[:half], rcond=None)
    residual = target[half:] - design[half:] @ coefficients
    return 1.0 - residual.var(axis=0).sum() / target[half:].var(axis=0).sum()


def wave_regressors(motion):
    x, y = motion[:, 0], motion[:, 1]
    return {"energy": (x * x + y * y)[:, None],
            "direction": np.column_stack((x * x, y * y, x * y))}


def explain_run(path, skip):
    dt, keep, data = read_run_datasets(path, (
        "/observer/bias", "/observer/wave_motion", "/environment/waves_drift",
        "/vessel/pose_true", "/vessel/pose_low_frequency"), skip, 200)
    drift = rotate(data["/environment/waves_drift"], data["/vessel/pose_low_frequency"][:, 5])
    bias = trailing_mean(data["/observer/bias"][:, :2], EXPLAIN_WINDOW)
    motions = {"filter": data["/observer/wave_motion"][:, :2],
               "true": (data["/vessel/pose_true"][:, :2] -
                        data["/vessel/pose_low_frequency"][:, :2])}
    shares = {"drift": explained_out_of_sample(
        bias[keep], trailing_mean(first_order_lag(drift, EXPLAIN_LAG, dt), EXPLAIN_WINDOW)[keep])}
    for source, motion in motions.items():
        for kind, features in wave_regressors(motion).items():
            shares[f"{source}, {kind}"] = explained_out_of_sample(
                bias[keep], trailing_mean(features, EXPLAIN_WINDOW)[keep])
    std = math.sqrt(bias[keep].var(axis=0).sum())
    return {"run": str(path), "bias_std": std,
            "left_after_drift": std * math.sqrt(max(0.0, 1.0 - shares["drift"])),
            "explained": shares}


def explain(directory, skip):
    result = []
    for block, runs in intact_runs_by_block(directory).items():
        result.append({"block": block, "runs": [explain_run(run, skip) for run in runs]})
    return result


def print_explained(result):
    print("share of the bias's 15 s mean (Earth axes) explained out of sample by a linear "
          "regression: median [least, most] over the block's runs")
    for entry in result:
        runs = entry["runs"]
        print(f"\n{entry['block']}: {len(runs)} intact runs; bias std "
              f"{statistics.median(r['bias_std'] for r in runs) / 1e6:.2f} MN, left after the "
              f"true drift {statistics.median(r['left_after_drift'] for r in runs) / 1e6:.2f} MN "
              f"(medians)")
        for name in runs[0]["explained"]:
            values = sorted(r["explained"][name] for r in runs)
            print(f"  {name:18s} {statistics.median(values):5.2f} [{values[0]:.2f}, "
                  f"{values[-1]:.2f}]")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", type=Path)
    parser.add_argument("--static", type=Path,
                        help="`moorsim static SCENARIO --json` for the campaign's mooring "
                             "(required unless --explain)")
    parser.add_argument("--explain", action="store_true",
                        help="how much of the bias a drift model explains (see above)")
    parser.add_argument("--rate", type=float, action="append",
                        help="false alarms per hour (repeatable; default 0.01 and 1)")
    parser.add_argument("--share", type=float, action="append",
                        help="share of the line's load lost (repeatable; default 1 and 0.7)")
    parser.add_argument("--lag", type=float, default=300.0,
                        help="Bartlett lag window [s] (default 300)")
    parser.add_argument("--skip", type=float, default=300.0,
                        help="start-up left out of each run [s] (default 300)")
    parser.add_argument("--target", type=float, default=30.0,
                        help="delay [s] whose share of exceeding breaks is counted (default 30)")
    parser.add_argument("--off-bow", type=float,
                        help="only runs whose mean wave drift comes from within this angle "
                             "of the bow [deg] (default all)")
    parser.add_argument("--json", type=Path, help="write every number to this file")
    args = parser.parse_args(argv)
    if args.explain:
        if not args.skip >= 0.0:
            print(f"attainable: --skip {args.skip} must be >= 0", file=sys.stderr)
            return EXIT_BAD_INPUT
        try:
            result = explain(args.directory, args.skip)
        except InputError as error:
            print(f"attainable: {error}", file=sys.stderr)
            return EXIT_BAD_INPUT
        print_explained(result)
        if args.json:
            args.json.write_text(json.dumps({"skip": args.skip, "blocks": result}, indent=1))
        return 0
    if args.static is None:
        print("attainable: --static is required (unless --explain)", file=sys.stderr)
        return EXIT_BAD_INPUT
    rates = args.rate or [0.01, 1.0]
    shares = args.share or [1.0, 0.7]
    for name, values in (("--rate", rates), ("--share", shares)):
        if any(not (v > 0.0) or (name == "--share" and v > 1.0) for v in values):
            print(f"attainable: {name} {values}: each must be > 0" +
                  (" and <= 1" if name == "--share" else ""), file=sys.stderr)
            return EXIT_BAD_INPUT
    if args.off_bow is not None and not 0.0 <= args.off_bow <= 180.0:
        print(f"attainable: --off-bow {args.off_bow} must be in [0, 180]", file=sys.stderr)
        return EXIT_BAD_INPUT
    if not (args.lag > 0.0 and args.skip >= 0.0 and args.target > 0.0):
        print(f"attainable: --lag {args.lag} and --target {args.target} must be > 0, "
              f"--skip {args.skip} >= 0",
              file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        result = analyze(args.directory, read_line_loads(args.static), rates, shares,
                         args.lag, args.skip, args.target, args.off_bow)
    except InputError as error:
        print(f"attainable: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    if not result:
        print(f"attainable: {args.directory}: no intact run has its mean drift within "
              f"{args.off_bow:g} deg of the bow", file=sys.stderr)
        return EXIT_BAD_INPUT
    print_table(result, args.target)
    if args.json:
        args.json.write_text(json.dumps({"lag": args.lag, "skip": args.skip,
                                         "target": args.target,
                                         "blocks": result}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
