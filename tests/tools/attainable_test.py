#!/usr/bin/python3
"""Checks tools/attainable.py against independent references: the long-run covariance of a
first-order autoregression (closed form), the Brownian CUSUM's mean delays (Monte-Carlo of
the discretised sum, with Siegmund's correction for the overshoot), the inverse Gaussian
median (numpy's Wald sampler), the whole tool on a synthetic campaign whose disturbance
is known, with its bad inputs, and --explain on a run whose drift is known.
Usage: attainable_test.py SOURCE_DIR"""

import contextlib
import io
import json
import math
import sys
import tempfile
from pathlib import Path

import h5py
import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, str(Path(sys.argv[1]) / "tools"))
import attainable  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAILED: {what}")


def ar1(rng, n, rho, innovation_covariance):
    """x_t = rho x_{t-1} + e_t, started stationary; long-run covariance Sigma_e / (1 - rho)^2."""
    chol = np.linalg.cholesky(innovation_covariance)
    e = rng.standard_normal((n, 2)) @ chol.T
    x = np.empty((n, 2))
    x[0] = e[0] / math.sqrt(1.0 - rho * rho)
    for t in range(1, n):
        x[t] = rho * x[t - 1] + e[t]
    return x


rng = np.random.default_rng(20261125)

# 1. Long-run covariance of an AR(1): within 5 % (lag window 400 against a 10-sample memory).
sigma_e = np.array([[1.0, 0.3], [0.3, 0.5]])
rho = 0.9
x = ar1(rng, 200_000, rho, sigma_e)
estimate = attainable.long_run_covariance(x, 400)
exact = sigma_e / (1.0 - rho) ** 2
check(np.allclose(estimate, exact, rtol=0.05, atol=0.05 * exact[0, 0]),
      f"AR(1) long-run covariance {estimate.tolist()} vs {exact.tolist()}")

# 2. The CUSUM threshold solves e^h - h - 1 = g over six decades.
for g in (1e-7, 1e-3, 0.5, 3.0, 1e2, 1e6):
    h = attainable.cusum_threshold(g)
    check(abs(math.expm1(h) - h - g) <= 1e-9 * max(g, 1e-6), f"threshold for g = {g}: h = {h}")


# 3. Mean times of the Brownian CUSUM (drift -+I, variance rate 2I) to h, without and with
#    the change, against the discretised sum on 4000 paths (dt = 1e-3): the discrete sum
#    overshoots h by 0.5826 sigma sqrt(dt) on average (Siegmund 1985), so the formula is
#    taken at h + that. Tolerance 5 % (the estimates' standard error is ~1.6 %).
def simulated_mean_time(drift, information, h, dt=1e-3, paths=4000):
    s = np.zeros(paths)
    time = np.zeros(paths)
    running = np.ones(paths, dtype=bool)
    step_std = math.sqrt(2.0 * information * dt)
    while running.any():
        active = np.flatnonzero(running)
        s[active] = np.maximum(0.0, s[active] + drift * dt +
                               step_std * rng.standard_normal(active.size))
        time[active] += dt
        running[active[s[active] >= h]] = False
    return time.mean()


information, h = 1.0, 2.0
shifted = h + 0.5826 * math.sqrt(2.0 * information * 1e-3)
delay = simulated_mean_time(information, information, h)
check(abs(delay / attainable.cusum_mean_delay(shifted, information) - 1.0) < 0.05,
      f"CUSUM mean delay {delay} vs {attainable.cusum_mean_delay(shifted, information)}")
to_false_alarm = simulated_mean_time(-information, information, h)
formula = (math.exp(shifted) - shifted - 1.0) / information
check(abs(to_false_alarm / formula - 1.0) < 0.05,
      f"CUSUM mean time to a false alarm {to_false_alarm} vs {formula}")

# 4. The first passage's median against the inverse Gaussian sampled (1 %).
for information, h in ((0.05, 10.0), (2.0, 3.0)):
    sample = rng.wald(h / information, h * h / (2.0 * information), 400_000)
    median = attainable.first_passage_median(h, information)
    check(abs(median / np.median(sample) - 1.0) < 0.01,
          f"first-passage median {median} vs sampled {np.median(sample)}")

# 5. The tool on a synthetic campaign: two intact runs at heading 30 deg whose drift (hull
#    axes) and bias (Earth axes) are AR(1) sequences of known long-run covariance, and a
#    failure run that must be left out. Line 1's anchor lies ahead of the hull (bearing 30
#    deg), line 2's on its starboard beam; the bound for each follows from the closed form.
with tempfile.TemporaryDirectory() as scratch:
    directory = Path(scratch) / "campaign"
    (directory / "rows").mkdir(parents=True)
    heading = math.radians(30.0)
    rotation = np.array([[math.cos(heading), -math.sin(heading)],
                         [math.sin(heading), math.cos(heading)]])  # hull -> Earth
    anchors = np.array([[1000.0 * math.cos(heading), 1000.0 * math.sin(heading), 1000.0],
                        [-1000.0 * math.sin(heading), 1000.0 * math.cos(heading), 1000.0]])
    drift_e = np.diag([1e10, 2.5e9])  # N^2 per sample: surge larger, as head seas give
    bias_e = np.array([[4e10, 1e10], [1e10, 1e10]])  # hull axes
    n = 40_000
    for run, failure_line in ((0, 0), (1, 0), (2, 1)):
        (directory / "rows" / f"{run:08d}.json").write_text(json.dumps(
            {"block": "rough", "status": "ok",
             "failure": {"line": failure_line, "time": 100.0, "mode": "fairlead"}
             if failure_line else None}))
        (directory / "runs" / f"{run:08d}").mkdir(parents=True)
        drift = ar1(rng, n, 0.9, drift_e) - [5e5, 0.0]  # pushed aft: waves from ahead
        bias = ar1(rng, n, 0.8, bias_e) @ rotation.T
        pose = np.zeros((n, 6))
        pose[:, 5] = heading
        with h5py.File(directory / "runs" / f"{run:08d}" / "run.h5", "w") as f:
            f["time"] = np.arange(n, dtype=float)
            f["vessel/pose_low_frequency"] = pose
            f["environment/waves_drift"] = np.column_stack((drift, np.zeros((n, 4))))
            f["observer/bias"] = np.column_stack((bias, np.zeros(n)))
            f["mooring/anchors"] = anchors
    static = Path(scratch) / "static.json"
    load = 4e6
    static.write_text(json.dumps({"lines": [{"id": 1, "horizontal_tension": load},
                                            {"id": 2, "horizontal_tension": load}]}))
    out = Path(scratch) / "bound.json"
    with contextlib.redirect_stdout(io.StringIO()):
        code = attainable.main([str(directory), "--static", str(static), "--rate", "0.01",
                                "--share", "1", "--lag", "300", "--skip", "0", "--json",
                                str(out)])
    check(code == 0, f"exit code {code} on the synthetic campaign")
    result = json.loads(out.read_text())["blocks"]
    check(len(result) == 1 and result[0]["runs"] == 2, "two intact runs read, the failure left out")
    block = result[0]
    check(all(abs(a) < 1.0 for a in block["drift_from"]), f"drift from ahead: {block['drift_from']}")
    for source, sigma, rho in (("drift", drift_e, 0.9), ("bias", bias_e, 0.8)):
        exact = sigma / (1.0 - rho) ** 2
        got = np.array(block["sources"][source]["long_run_covariance"])
        check(np.allclose(got, exact, rtol=0.1, atol=0.1 * exact[0, 0]),
              f"{source} long-run covariance {got.tolist()} vs {exact.tolist()}")
        inverse = np.linalg.inv(exact)
        informations = [0.5 * load * load * inverse[0, 0], 0.5 * load * load * inverse[1, 1]]
        bound = block["sources"][source]["bounds"][0]
        check(abs(bound["worst"]["information"] / min(informations) - 1.0) < 0.1,
              f"{source} worst information {bound['worst']['information']} vs "
              f"{min(informations)}")
        medians = sorted(attainable.bound(i, 0.01)[2] for i in informations)
        check(abs(bound["median_delay"]["most"] / medians[-1] - 1.0) < 0.1,
              f"{source} longest median delay {bound['median_delay']['most']} vs {medians[-1]}")

    # Bad input: one line naming what is wrong, exit 2.
    def run_bad(args, expected):
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            code = attainable.main(args)
        message = stderr.getvalue().strip()
        check(code == 2 and expected in message and "\n" not in message,
              f"bad input {args}: exit {code}, message '{message}'")

    run_bad([str(Path(scratch) / "nothing"), "--static", str(static)], "no finished runs")
    run_bad([str(directory), "--static", str(Path(scratch) / "none.json")], "none.json")
    run_bad([str(directory), "--static", str(static), "--share", "1.5"], "--share")
    run_bad([str(directory), "--static", str(static), "--off-bow", "200"], "--off-bow")
    with h5py.File(directory / "runs" / "00000001" / "run.h5", "a") as f:
        del f["observer/bias"]
    run_bad([str(directory), "--static", str(static)], "no dataset /observer/bias")

# 6. --explain on a synthetic run whose drift is known: waves whose direction wanders slowly
#    (theta, AR(1) with a 200 s memory) under a slowly varying envelope; the drift is a
#    surge gain on x^2 and a sway gain on xy (which changes sign with the side the waves
#    come from), the bias that drift through the filter's 15 s lag plus a little white
#    noise, and the filter's wave motion the true one plus half its size in noise. The true
#    drift must explain nearly all of it (> 0.9), the direction regressors of the true
#    motion most (> 0.6, the lag they leave out costs a little), the energy alone less than
#    half as much, and the noisy motion less than the true one.
with tempfile.TemporaryDirectory() as scratch:
    directory = Path(scratch) / "campaign"
    (directory / "rows").mkdir(parents=True)
    (directory / "runs" / "00000000").mkdir(parents=True)
    (directory / "rows" / "00000000.json").write_text(json.dumps(
        {"block": "turning", "status": "ok", "failure": None}))
    n = 7200
    t = np.arange(n, dtype=float)

    def unit_ar1(memory):
        rho = math.exp(-1.0 / memory)
        return ar1(rng, n, rho, np.eye(2) * (1.0 - rho * rho))[:, 0]

    theta = 0.3 * unit_ar1(200.0)
    envelope = np.exp(0.5 * unit_ar1(60.0))
    carrier = envelope * np.cos(2.0 * math.pi * t / 11.0)
    motion = np.column_stack((carrier * np.cos(theta), carrier * np.sin(theta)))
    drift = np.column_stack((-2e6 * motion[:, 0] ** 2, 6e6 * motion[:, 0] * motion[:, 1]))
    bias = attainable.first_order_lag(drift, attainable.EXPLAIN_LAG, 1.0)
    bias += 2e4 * rng.standard_normal((n, 2))
    noisy = motion + 0.5 * motion.std(axis=0).mean() * rng.standard_normal((n, 2))
    pose = np.zeros((n, 6))
    with h5py.File(directory / "runs" / "00000000" / "run.h5", "w") as f:
        f["time"] = t
        f["vessel/pose_low_frequency"] = pose
        f["vessel/pose_true"] = np.column_stack((motion, np.zeros((n, 4))))
        f["environment/waves_drift"] = np.column_stack((drift, np.zeros((n, 4))))
        f["observer/bias"] = np.column_stack((bias, np.zeros(n)))
        f["observer/wave_motion"] = np.column_stack((noisy, np.zeros(n)))
    out = Path(scratch) / "explained.json"
    with contextlib.redirect_stdout(io.StringIO()):
        code = attainable.main([str(directory), "--explain", "--skip", "0", "--json", str(out)])
    check(code == 0, f"exit code {code} of --explain")
    shares = json.loads(out.read_text())["blocks"][0]["runs"][0]["explained"]
    check(shares["drift"] > 0.9, f"true drift explains {shares['drift']}")
    check(shares["true, direction"] > 0.6, f"true direction explains {shares['true, direction']}")
    check(shares["true, energy"] < 0.5 * shares["true, direction"],
          f"energy {shares['true, energy']} against direction {shares['true, direction']}")
    check(shares["filter, direction"] < shares["true, direction"] - 0.02,
          f"noisy motion {shares['filter, direction']} against true {shares['true, direction']}")
    with h5py.File(directory / "runs" / "00000000" / "run.h5", "a") as f:
        del f["observer/wave_motion"]
    stderr = io.StringIO()
    with contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
        code = attainable.main([str(directory), "--explain"])
    message = stderr.getvalue().strip()
    check(code == 2 and "no dataset /observer/wave_motion" in message,
          f"--explain without the wave motion: exit {code}, '{message}'")

if failures:
    sys.exit(1)
print("attainable: all checks passed")
