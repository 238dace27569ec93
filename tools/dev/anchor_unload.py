#!/usr/bin/env python3
"""How long an anchor release's load takes to leave, against how long the fused detector
takes to name it, run by run.

Runs the anchor-release block of the sensor-fault campaigns (the turret-forward mooring,
Hs 2.5, 4 and 6 m, 8 runs per sea state, a load cell on every fairlead) under its own seed,
keeping every run's run.h5, then reads the released line's fairlead tension: from its mean
over the 100 s before the release to the lowest its 10 s moving mean falls afterwards, the
time it takes to shed half and 90 % of that drop. Run from the repository root after a
release build:
    tools/dev/anchor_unload.py [--out DIR]
"""
import argparse
import importlib.util
import json
import statistics
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
MOORSIM = ROOT / "build/release/tools/moorsim"


def campaign_text():
    spec = importlib.util.spec_from_file_location(
        "campaigns", ROOT / "tools/dev/sensor_fault_campaigns.py")
    campaigns = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(campaigns)
    body = campaigns.preamble("anchor_unload", 3699, "# Anchor releases: load leaving, detection.")
    body = [line.replace("../library/", f"{ROOT}/scenarios/library/") for line in body]
    body = [line for line in body if not line.startswith("    - {type:") or "fused" in line]
    body.append(campaigns.failure_block("anchor"))
    return "\n".join(body) + "\n"


def shed_times(run_h5, line, release):
    """Seconds after the release at which the line's tension has shed 50 and 90 % of its drop."""
    with h5py.File(run_h5) as f:
        t = f["/time"][:]
        tension = f["/mooring/fairlead_tension"][:, line - 1]
    step = t[1] - t[0]
    width = max(1, int(round(10.0 / step)))
    mean = np.convolve(tension, np.ones(width) / width, mode="same")
    before = tension[(t > release - 100) & (t < release)].mean()
    after = (t > release + 5) & (t < t[-1] - 5)
    lowest = mean[after].min()

    def shed(share):
        idx = np.where((t > release) & (mean <= before - share * (before - lowest)))[0]
        return t[idx[0]] - release

    return before, lowest, shed(0.5), shed(0.9)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out/anchor_unload")
    out = Path(parser.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    yaml = out / "anchor_unload.yaml"
    yaml.write_text(campaign_text())
    subprocess.run([str(MOORSIM), "batch", str(yaml), "--out", str(out / "batch"), "--keep-runs",
                    "--quiet"], check=True)
    rows = [json.loads(p.read_text()) for p in sorted((out / "batch/rows").glob("*.json"))]
    by_sea = {}
    for r in rows:
        failure = r["failure"]
        run_h5 = out / "batch/runs" / f"{r['run']:08d}" / "run.h5"
        before, lowest, half, most = shed_times(run_h5, failure["line"], failure["time"])
        verdict = r["detectors"]["fused"]
        delay = verdict["isolation_delay"] if verdict["isolated_line"] == failure["line"] else None
        by_sea.setdefault(float(r["factors"]["environment.waves.hs"]), []).append(
            (before, lowest, half, most, delay))
    print("| Hs | tension before / lowest after | half shed, median | 90 % shed, median (least) "
          "| named, median / largest delay | named before 90 % shed |")
    print("|---|---|---|---|---|---|")
    for hs, runs in sorted(by_sea.items()):
        delays = [r[4] for r in runs if r[4] is not None]
        before = sum(1 for r in runs if r[4] is not None and r[4] <= r[3])
        print(f"| {hs:g} m | {statistics.median(r[0] for r in runs) / 1e6:.2f} / "
              f"{statistics.median(r[1] for r in runs) / 1e6:.2f} MN | "
              f"{statistics.median(r[2] for r in runs):.0f} s | "
              f"{statistics.median(r[3] for r in runs):.0f} s ({min(r[3] for r in runs):.0f} s) | "
              f"{len(delays)}/{len(runs)}, {statistics.median(delays):.0f} / {max(delays):.0f} s | "
              f"{before}/{len(runs)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
