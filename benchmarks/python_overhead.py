"""The Python module's cost over the C API's, on the same loops as api_benchmark.cc:
the seed mooring's lines stepped every 0.1 s along a surge-heave harmonic, the seed case's
plant advanced one second at a time with its pose and tensions read (a 1 Hz control loop),
and the lines' and the plant's save and restore.

    PYTHONPATH=build/release/python python3 benchmarks/python_overhead.py
    build/release/benchmarks/moorsim_benchmarks --benchmark_filter='BM_CApi|BM_Coupled'
"""
import os
import time

import numpy as np

import moorsim

SEED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios", "library",
                    "seed_tapm.yaml")


def motion(t):
    ws, wh = 2 * np.pi / 60.0, 2 * np.pi / 10.0
    x = np.array([5.0 * np.sin(ws * t), 0, np.sin(wh * t), 0, 0, 0])
    xd = np.array([5.0 * ws * np.cos(ws * t), 0, wh * np.cos(wh * t), 0, 0, 0])
    return x, xd


def per_call(function, n):
    start = time.perf_counter()
    for _ in range(n):
        function()
    return (time.perf_counter() - start) / n


def main():
    lines = moorsim.Lines(SEED)
    lines.init(*motion(0.0))
    clock = {"t": 0.0}

    def step():
        clock["t"] += 0.1
        lines.step(*motion(clock["t"]), 0.1)

    best = min(per_call(step, 2000) for _ in range(3))
    print(f"Lines.step, 0.1 s: {best * 1e6:.0f} us per step")
    state = lines.save()
    print(f"Lines.save: {min(per_call(lines.save, 2000) for _ in range(3)) * 1e6:.1f} us, "
          f"{len(state)} bytes")
    print(f"Lines.restore: {min(per_call(lambda: lines.restore(state), 2000) for _ in range(3)) * 1e6:.1f} us")

    plant = moorsim.Plant(SEED, seed=1)
    seconds = {"t": 0.0}

    def second():
        seconds["t"] += 1.0
        plant.advance_to(seconds["t"])
        row = plant.record()
        return row["pose"], row["fairlead_tension"]

    print(f"Plant, 1 s with pose and tensions read: {per_call(second, 600) * 1e6:.0f} us per second")
    saved = plant.save()
    fresh = moorsim.Plant(SEED, seed=1)
    start = time.perf_counter()
    fresh.restore(saved)
    print(f"Plant.restore at {plant.time:.0f} s (replayed): {time.perf_counter() - start:.3f} s")


if __name__ == "__main__":
    main()
