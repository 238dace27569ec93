"""A campaign's table in pandas: per detector, how often it named the parted line (with a
Wilson 95 % interval) and how fast (median and 90th percentile delay).

    PYTHONPATH=build/release/python python3 examples/python/campaign_analysis.py [RESULTS_DIR]

With a results directory (`moorsim batch ... --out DIR`, or tools/main.sh's
out/thesis_detection_small) it reads that campaign; without one it runs a small campaign
of its own first (four lines parting once each on the thesis case, 600 s runs).
"""
import os
import sys
import tempfile

import numpy as np

import moorsim

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "..", "..", "scenarios", "library", "thesis_no_failure_current.yaml")
CAMPAIGN = f"""name: example
scenario: {SCENARIO}
seed: 4
blocks:
  - name: failures
    set: {{simulation.duration: 600, failure.mode: fairlead}}
    factors:
      - {{key: failure.line, values: [2, 4, 6, 8]}}
      - {{key: failure.time, uniform: [200, 300]}}
    seeds: 1
"""


def wilson(successes, n, z=1.96):
    """The Wilson score interval of a proportion."""
    if n == 0:
        return float("nan"), float("nan")
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return centre - half, centre + half


def main():
    if len(sys.argv) > 1:
        table = moorsim.read_campaign(sys.argv[1])
    else:
        work = tempfile.mkdtemp(prefix="moorsim-campaign-")
        path = os.path.join(work, "campaign.yaml")
        with open(path, "w") as f:
            f.write(CAMPAIGN)
        table = moorsim.run_campaign(path, out=os.path.join(work, "out"), threads=2)
    failures = table[table["failure_line"] > 0]
    detectors = sorted({c.split(".")[0] for c in table.columns if c.endswith(".alarm_time")})
    print(f"{len(failures)} runs with a failure, {len(table) - len(failures)} intact")
    print(f"{'detector':10} {'named':>7} {'95 % interval':>15} {'median delay':>13} {'p90':>7}")
    for d in detectors:
        named = failures[f"{d}.isolated_line"] == failures["failure_line"]
        low, high = wilson(int(named.sum()), len(failures))
        delays = failures.loc[named, f"{d}.delay"]
        print(f"{d:10} {named.sum():3d}/{len(failures):<3d} {low:6.2f} .. {high:4.2f} "
              f"{delays.median():11.0f} s {delays.quantile(0.9):5.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
