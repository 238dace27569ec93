"""The Python module under misuse and Ctrl-C: integers out of range and of the wrong type
raise ValueError, IndexError or TypeError naming the argument; tension arrays of the wrong
width are refused; a pose where a line cannot hang is bad input; and Ctrl-C stops every
long call within a second, leaving the object usable (each call is run in a child Python
that the test interrupts with SIGINT, as a terminal's Ctrl-C does)."""
import os
import queue
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import moorsim

SOURCE = os.environ["MOORSIM_SOURCE_DIR"]
THESIS = os.path.join(SOURCE, "scenarios/library/thesis_line6_current.yaml")
SEED = os.path.join(SOURCE, "scenarios/library/seed_tapm.yaml")
ZEROS = np.zeros(6)


def test_integers_out_of_range_or_of_another_type_name_the_argument():
    lines = moorsim.Lines(SEED)
    lines.init(ZEROS, ZEROS)
    with pytest.raises(IndexError, match=r"^node 1000000000000 is not one of the nodes 1\.\.49$"):
        lines.part(1, where="node", node=10**12)
    with pytest.raises(IndexError, match=r"^line 1000000000000 is not one of the lines 1\.\.8$"):
        lines.node_positions(10**12)
    with pytest.raises(IndexError, match=r"^line -1 is not one of the lines 1\.\.8$"):
        lines.segment_tensions(-1)
    with pytest.raises(TypeError, match="^line must be an integer, not float$"):
        lines.node_count(1.0)
    with pytest.raises(ValueError,
                       match=r"^seed 18446744073709551616 is not in 0\.\.18446744073709551615$"):
        moorsim.Plant(THESIS, seed=2**64)
    with pytest.raises(ValueError, match=r"^seed -1 is not in 0\.\."):
        moorsim.Plant(THESIS, seed=-1)
    with pytest.raises(TypeError, match="^seed must be an integer, not str$"):
        moorsim.Plant(THESIS, seed="1")
    # Nothing was done to the lines by the refused calls.
    assert lines.time == 0.0
    assert lines.fairlead_tensions().shape == (8,)


def test_a_pose_where_a_line_cannot_hang_is_bad_input():
    lines = moorsim.Lines(SEED)
    with pytest.raises(moorsim.InputError,
                       match="^the body at x, y, z = 5000, 0, 0 m puts a fairlead where its line "
                             "cannot hang: line 1: .*cannot reach"):
        lines.init(np.array([5000.0, 0, 0, 0, 0, 0]), ZEROS)
    lines.init(ZEROS, ZEROS)  # and the lines can start again where they can
    assert np.all(lines.fairlead_tensions() > 1e6)


def test_what_looks_wrong_but_is_done_is_a_warning():
    lines = moorsim.Lines(SEED)
    with pytest.warns(moorsim.MoorsimWarning, match="^line 1's fairlead is 488 m above the water"):
        lines.init(np.array([0.0, 0, -500, 0, 0, 0]), ZEROS)
    lines.init(ZEROS, ZEROS)
    with pytest.warns(moorsim.MoorsimWarning, match="^the body moves 1000 m and turns 0 rad in a "
                                                    "step of 0.1 s at t = 0 s"):
        lines.step(np.array([1000.0, 0, 0, 0, 0, 0]), ZEROS, 0.1)


def test_detect_takes_one_tension_column_per_line_as_the_program_does():
    n = 10
    t = np.arange(n, dtype=float)
    pose = np.zeros((n, 3))
    for width in (3, 9):
        with pytest.raises(ValueError, match="^tensions must have one row per time and 8 columns$"):
            moorsim.detect(THESIS, t, pose, tensions=np.zeros((n, width)))


def test_a_step_longer_than_a_day_or_shorter_than_a_nanosecond_is_refused():
    lines = moorsim.Lines(SEED)
    lines.init(ZEROS, ZEROS)
    for dt in (1e6, 5e-324, 0.0):
        with pytest.raises(moorsim.InputError, match="must be a number from 1e-09 to 86400 s"):
            lines.step(ZEROS, ZEROS, dt)
    plant = moorsim.Plant(THESIS, seed=1)
    with pytest.raises(moorsim.InputError, match="one advance spans at most 86400 s"):
        plant.advance_to(1e300)
    plant.advance_to(3.0)
    with pytest.raises(moorsim.InputError,
                       match=r"^time 2\.9999999999999996 s is behind the plant's 3 s$"):
        plant.advance_to(np.nextafter(3.0, 0.0))


def _misuses():
    """Every function of the module with arguments of the wrong type, shape or size: (name,
    call) pairs."""
    lines = moorsim.Lines(SEED)
    fresh = moorsim.Lines(SEED)
    lines.init(ZEROS, ZEROS)
    plant = moorsim.Plant(THESIS, seed=1)
    t, pose = np.arange(5.0), np.zeros((5, 3))
    cases = []
    for name, bad in [("None", None), ("str", "x"), ("list of 5", [0.0] * 5),
                      ("2-D", np.zeros((2, 6))), ("strings", np.array(["a"] * 6)),
                      ("empty", np.zeros(0)), ("huge int", 10**400), ("nan", float("nan"))]:
        cases += [
            (f"Lines.init(x={name})", lambda b=bad: fresh.init(b, ZEROS)),
            (f"Lines.init(xd={name})", lambda b=bad: fresh.init(ZEROS, b)),
            (f"Lines.step(x={name})", lambda b=bad: lines.step(b, ZEROS, 0.1)),
            (f"Lines.step(dt={name})", lambda b=bad: lines.step(ZEROS, ZEROS, b)),
            (f"Lines.node_count({name})", lambda b=bad: lines.node_count(b)),
            (f"Lines.segment_tensions({name})", lambda b=bad: lines.segment_tensions(b)),
            (f"Lines.node_positions({name})", lambda b=bad: lines.node_positions(b)),
            (f"Lines.part({name})", lambda b=bad: fresh.part(b)),
            (f"Lines.part(where={name})", lambda b=bad: lines.part(1, where=b)),
            (f"Lines.part(node={name})", lambda b=bad: lines.part(1, where="node", node=b)),
            (f"Lines.restore({name})", lambda b=bad: lines.restore(b)),
            (f"Plant(seed={name})", lambda b=bad: moorsim.Plant(THESIS, seed=b)),
            (f"Plant.advance_to({name})", lambda b=bad: plant.advance_to(b)),
            (f"Plant.set_thrust({name})", lambda b=bad: plant.set_thrust(b) if b is not None
             else plant.set_thrust([float("inf"), 0, 0])),
            (f"Plant.set_external_load({name})", lambda b=bad: plant.set_external_load(b)),
            (f"Plant.restore({name})", lambda b=bad: plant.restore(b)),
            (f"detect(time={name})", lambda b=bad: moorsim.detect(THESIS, b, pose)),
            (f"detect(pose={name})", lambda b=bad: moorsim.detect(THESIS, t, b)),
            (f"detect(thrust={name})",
             lambda b=bad: moorsim.detect(THESIS, t, pose, thrust=b if b is not None else [])),
            (f"detect(tensions={name})",
             lambda b=bad: moorsim.detect(THESIS, t, pose, tensions=b if b is not None else [])),
            (f"detect(set={name})", lambda b=bad: moorsim.detect(THESIS, t, pose, set=b or 5)),
            (f"run(set={name})", lambda b=bad: moorsim.run(THESIS, set={"simulation.duration": b})),
            (f"Lines({name})", lambda b=bad: moorsim.Lines(b)),
            (f"Lines.from_yaml({name})", lambda b=bad: moorsim.Lines.from_yaml(b)),
            (f"read_run({name})", lambda b=bad: moorsim.read_run(b)),
        ]
    # Arrays of the right shape but another size, and states of another kind.
    cases += [
        ("Lines.restore(a plant's state)", lambda: lines.restore(plant.save())),
        ("Plant.restore(the lines' state)", lambda: plant.restore(lines.save())),
        ("Lines.restore(cut short)", lambda: lines.restore(lines.save()[:-1])),
        ("Plant.restore(cut short)", lambda: plant.restore(plant.save()[:-3])),
        ("detect(pose with 2 columns)", lambda: moorsim.detect(THESIS, t, np.zeros((5, 2)))),
        ("detect(pose with 4 rows)", lambda: moorsim.detect(THESIS, t, np.zeros((4, 3)))),
        ("detect(thrust with 2 rows)",
         lambda: moorsim.detect(THESIS, t, pose, thrust=np.zeros((2, 3)))),
        ("Plant.set_thrust(4 numbers)", lambda: plant.set_thrust([1.0, 2.0, 3.0, 4.0])),
    ]
    return cases


def test_every_function_refuses_wrong_types_shapes_and_sizes_with_a_python_error():
    allowed = (TypeError, ValueError, IndexError, RuntimeError, OverflowError, OSError,
               KeyError, moorsim.Error)
    wrong = []
    for name, call in _misuses():
        try:
            call()
        except allowed as e:
            # A refusal says what: a message of its own, never a bare exception.
            if not str(e):
                wrong.append(f"{name}: {type(e).__name__} without a message")
        except Exception as e:  # noqa: BLE001 - anything else is the defect looked for
            wrong.append(f"{name}: {type(e).__name__}: {e}")
    assert not wrong, "\n".join(wrong)


# The child: sets up one long call, says "ready", makes it, and reports how it ended and
# whether the object can go on.
CHILD = r"""
import sys, time
import numpy as np
import moorsim
what, thesis = sys.argv[1:3]
zeros = np.zeros(6)
if what == "step":  # steps of at most 10 ms: a day's step takes an hour
    lines = moorsim.Lines(thesis, overrides=["solver.max_step=0.01"])
    lines.init(zeros, zeros)
    call = lambda: lines.step(zeros, zeros, 86400.0)
    def usable():
        assert lines.time == 0.0, lines.time
        lines.step(zeros, zeros, 0.5)
        return lines.time == 0.5
elif what == "advance":
    plant = moorsim.Plant(thesis, seed=1)
    call = lambda: plant.advance_to(86400.0)
    def usable():
        reached = plant.time
        assert 0.0 < reached < 86400.0, reached
        plant.advance_to(reached + 2.0)
        return plant.time == reached + 2.0
elif what == "restore":
    saved = moorsim.Plant(thesis, seed=1)
    saved.advance_to(1500.0)
    state = saved.save()
    plant = moorsim.Plant(thesis, seed=1)
    call = lambda: plant.restore(state)
    def usable():
        # A fresh plant continues into the saved one: it stops where the replay was.
        reached = plant.time
        assert 0.0 < reached < 1500.0, reached
        plant.advance_to(1500.0)  # and goes on as the saved plant went, bit for bit
        return np.array_equal(plant.record()["pose"], saved.record()["pose"])
elif what == "detect":
    n = 2000000
    t = np.arange(n, dtype=float)
    pose = np.zeros((n, 3))
    call = lambda: moorsim.detect(thesis, t, pose)
    usable = lambda: True
print("ready", flush=True)
try:
    call()
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", time.monotonic(), flush=True)
    print("usable" if usable() else "spoilt", flush=True)
"""


def _lines_of(child):
    """The child's output lines as a queue, read on a thread: every wait is bounded."""
    lines = queue.Queue()

    def read():
        for line in child.stdout:
            lines.put(line.strip())
        lines.put(None)

    threading.Thread(target=read, daemon=True).start()
    return lines


@pytest.mark.parametrize("what", ["step", "advance", "restore", "detect"])
def test_ctrl_c_stops_a_long_call_within_a_second_and_leaves_it_usable(what):
    child = subprocess.Popen([sys.executable, "-c", CHILD, what, THESIS],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines = _lines_of(child)
    try:
        assert lines.get(timeout=120) == "ready"
        time.sleep(0.5)  # well inside the call, which takes an hour or more uninterrupted
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        ended = (lines.get(timeout=30) or "").split()
        assert ended and ended[0] == "interrupted", ended
        # CLOCK_MONOTONIC is the machine's: the two processes' readings compare.
        assert float(ended[1]) - sent < 1.0
        assert lines.get(timeout=120) == "usable"
        assert child.wait(timeout=60) == 0
    finally:
        if child.poll() is None:
            child.kill()
        child.wait()
    assert child.stderr.read() == ""
