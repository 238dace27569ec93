"""A detector of one's own, written in Python, beside moorsim's on the thesis case.

The coupled plant of the thesis case (line 6 parts at its fairlead at 400 s, 0.1 m/s
current, Hs 2.5 m waves) is stepped from Python once a second with the scenario's own
controller. The detector below sees what moorsim's detectors see, the measured position
and heading, and nothing else: it low-passes the position (a 60 s exponential average),
learns the intact wander of that average over the first 300 s, and declares a failure
when the average leaves its intact mean by more than six times that wander and 1 m. It
names the line whose anchor lies most nearly behind the drift (a parted line stops
pulling toward its anchor, so the vessel drifts away from it). The built-in DHT's verdict
is printed beside it.

    PYTHONPATH=build/release/python python3 examples/python/python_detector.py
"""
import os
import sys

import numpy as np

import moorsim

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "..", "..", "scenarios", "library", "thesis_line6_current.yaml")
# The scenario's anchors (mooring.lines[].anchor), north and east [m].
ANCHORS = np.array([[1950, 0], [0, 1950], [-1950, 0], [0, -1950],
                    [1378.9, 1378.9], [-1378.9, 1378.9], [-1378.9, -1378.9], [1378.9, -1378.9]])


class DriftDetector:
    """Low-passed position against its intact statistics; the line behind the drift."""

    def __init__(self, learn_until=300.0, time_constant=60.0):
        self.learn_until, self.time_constant = learn_until, time_constant
        self.average = None
        self.learned = []
        self.alarm = None

    def update(self, t, position):
        if np.any(np.isnan(position)):
            return
        if self.average is None:
            self.average = position.copy()
        self.average += (position - self.average) / self.time_constant
        if t <= self.learn_until:
            self.learned.append(self.average.copy())
            return
        history = np.array(self.learned)
        mean, wander = history.mean(axis=0), history.std(axis=0).max()
        drift = self.average - mean
        if self.alarm is None and np.linalg.norm(drift) > max(6 * wander, 1.0):
            # The anchor most nearly opposite the drift, seen from the mean position.
            toward = (ANCHORS - mean) / np.linalg.norm(ANCHORS - mean, axis=1)[:, None]
            line = int(np.argmin(toward @ (drift / np.linalg.norm(drift)))) + 1
            self.alarm = (t, line)


def main():
    plant = moorsim.Plant(SCENARIO, seed=1, overrides=["simulation.duration=800"])
    labels = plant.hypotheses
    detector = DriftDetector()
    dht_alarm = None
    for t in np.arange(1.0, 801.0):
        plant.advance_to(t)
        row = plant.record()
        detector.update(t, row["pose_measured"][:2])
        dht = row["detectors"][0]
        if dht["alarm"] and dht_alarm is None and t >= 400:
            dht_alarm = (t, labels[dht["hypothesis"]])
    print(f"line 6 parted at 400 s")
    print(f"python drift detector: " + (f"line {detector.alarm[1]} at {detector.alarm[0]:.0f} s"
                                        if detector.alarm else "no alarm"))
    print(f"moorsim DHT: " + (f"{dht_alarm[1]} at {dht_alarm[0]:.0f} s" if dht_alarm else "no alarm"))
    return 0 if detector.alarm and detector.alarm[1] == 6 else 1


if __name__ == "__main__":
    sys.exit(main())
