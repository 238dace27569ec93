"""A bank of moored-vessel models that branches: which line has parted, and since when?

The true vessel (surge and sway, its own integrator below) rides on the seed mooring's
lines (moorsim.Lines) under a steady 1 MN load toward north; line 3 parts at 30 s and the
vessel drifts to a new balance. Its position is measured at 1 Hz with 0.1 m noise.

The estimator runs one model of vessel and lines per hypothesis: every line intact, or
line j parted. A parted model must have parted when the real line did, so every second
each parted model whose hypothesis is not (yet) believed is branched afresh from the
intact model: the intact lines' state is saved and restored into it (moorsim's save and
restore, microseconds), the intact vessel's state copied, and its line parted there. The
measured positions weight the hypotheses (Bayes, with a small probability per second that
a line parts).

    PYTHONPATH=build/release/python python3 examples/python/particle_filter.py
"""
import os
import sys

import numpy as np

import moorsim

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "..", "..", "scenarios", "library", "seed_tapm.yaml")
LOAD = np.array([1.0e6, 0.0])   # steady load north, east [N]
MASS, DAMPING = 2.0e8, 1.0e7    # vessel mass with added mass [kg], damping [N s/m]
NOISE = 0.1                     # position measurement, standard deviation [m]
HAZARD = 1e-3                   # probability per second that a given line parts
PARTS_AT, PARTED = 30.0, 3
DT, DURATION = 0.2, 120.0


class Model:
    """A vessel in surge and sway on its own copy of the lines."""

    def __init__(self):
        self.lines = moorsim.Lines(SCENARIO)
        self.x, self.xd = np.zeros(6), np.zeros(6)
        self.force = self.lines.init(self.x, self.xd)

    def step(self, dt):
        """Semi-implicit Euler for the vessel, then the lines to its new pose."""
        acceleration = (self.force[:2] + LOAD - DAMPING * self.xd[:2]) / MASS
        self.xd[:2] += dt * acceleration
        self.x[:2] += dt * self.xd[:2]
        self.force = self.lines.step(self.x, self.xd, dt)

    def copy_from(self, other, state):
        """This model becomes `other`, whose lines' saved state is `state`."""
        self.lines.restore(state)
        self.x, self.xd, self.force = other.x.copy(), other.xd.copy(), other.force.copy()


def main():
    rng = np.random.default_rng(1)
    truth = Model()
    # The vessel at rest under the load first (about 1500 s), then everyone starts there.
    for _ in range(int(1800 / 1.0)):
        truth.step(1.0)
    start = truth.lines.save()
    lines = truth.lines.num_lines
    bank = [Model() for _ in range(lines + 1)]  # 0: intact, j: line j parted
    for model in [truth] + bank:
        model.copy_from(truth, start)
    posterior = np.zeros(lines + 1)
    posterior[0] = 1.0
    named = None
    t, k = 0.0, 0
    steps_per_sample = int(round(1.0 / DT))
    while t < DURATION - 1e-9:
        if k % steps_per_sample == 0:
            # Branch: the parted hypotheses not believed start again from the intact model.
            intact = bank[0].lines.save()
            for j in range(1, lines + 1):
                if posterior[j] < 0.01:
                    bank[j].copy_from(bank[0], intact)
                    bank[j].lines.part(j)
                    posterior[j] = posterior[0] * HAZARD
            posterior /= posterior.sum()
        for model in [truth] + bank:
            model.step(DT)
        t, k = t + DT, k + 1
        if abs(t - PARTS_AT) < 1e-9:
            truth.lines.part(PARTED)
        if k % steps_per_sample != 0:
            continue
        measured = truth.x[:2] + rng.normal(0.0, NOISE, 2)
        log_likelihood = np.array(
            [-0.5 * np.sum(((measured - m.x[:2]) / NOISE) ** 2) for m in bank])
        posterior *= np.exp(log_likelihood - log_likelihood.max())
        posterior /= posterior.sum()
        best = int(np.argmax(posterior))
        if best != 0 and posterior[best] > 0.99 and named is None:
            named = (best, t)
        if k % (10 * steps_per_sample) == 0:
            print(f"t {t:5.1f} s  x {truth.x[0]:7.3f} m  P(intact) {posterior[0]:.3f}  "
                  f"most likely: {'intact' if best == 0 else f'line {best}'} {posterior[best]:.3f}")
    if named is None:
        print("no line named")
        return 1
    print(f"named line {named[0]} at {named[1]:.0f} s (line {PARTED} parted at {PARTS_AT:.0f} s)")
    return 0 if named[0] == PARTED else 1


if __name__ == "__main__":
    sys.exit(main())
