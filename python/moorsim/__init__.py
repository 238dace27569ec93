"""moorsim from Python: moored-vessel simulation and mooring-line failure detection.

    import moorsim
    run = moorsim.run("scenarios/library/thesis_line6_current.yaml", set={"simulation.duration": 600})
    run.summary["detectors"]["dht"]["alarm_time"]     # what summary.json says
    run["mooring/fairlead_tension"]                    # NumPy arrays, as run.h5 holds them
    run.to_xarray()                                    # an xarray Dataset (python3-xarray)

    lines = moorsim.Lines("scenarios/library/seed_tapm.yaml")   # the lines for a coupling
    f = lines.init(x, xd); f = lines.step(x, xd, dt); state = lines.save(); lines.restore(state)

    plant = moorsim.Plant("scenario.yaml", seed=1)     # the coupled plant, stepped by you
    plant.set_thrust([X, Y, N]); plant.advance_to(10.0); plant.record()["pose_measured"]

    table = moorsim.run_campaign("campaign.yaml", out="out/c")   # a pandas DataFrame
    table = moorsim.read_campaign("out/c")
    verdicts = moorsim.detect("scenario.yaml", time, pose)       # detection on arrays

Conventions are moorsim's: SI units, NED (x north, y east, z down), angles in radians,
lines numbered from 1. Errors raise moorsim.InputError (bad input: a scenario, a value),
moorsim.SolverError (the integrator) or moorsim.Error; bad arguments raise ValueError,
IndexError (a line or node that is not there) or TypeError. What a call does although it
looks wrong (a fairlead far above the water, a body faster than a moored body can be) is a
moorsim.MoorsimWarning. Ctrl-C stops a long call within a second (KeyboardInterrupt): the
lines as they were before a step, the plant at the instant it reached.
"""

import json
import os
import shutil
import tempfile

import numpy as np

from ._moorsim import Error, InputError, Lines, MoorsimWarning, Plant, SolverError, __version__
from . import _moorsim

__all__ = [
    "Error", "InputError", "SolverError", "MoorsimWarning", "Lines", "Plant", "Run", "run",
    "read_run",
    "run_campaign", "read_campaign", "read_design", "detect", "__version__",
]


def _overrides(set=None, seed=None, duration=None):
    """key.path=value strings, as `moorsim run --set` takes them, from a dict."""
    if set is not None and not isinstance(set, dict):
        raise TypeError(f"set must be a dict of key paths and values, not {type(set).__name__}")
    items = []
    for key, value in (set or {}).items():
        if isinstance(value, bool):
            text = "true" if value else "false"
        elif isinstance(value, (list, tuple, dict)):
            text = json.dumps(value)
        else:
            text = str(value)
        items.append(f"{key}={text}")
    if seed is not None:
        items.append(f"simulation.seed={int(seed)}")
    if duration is not None:
        items.append(f"simulation.duration={float(duration)!r}")
    return items


def _text(value):
    return value.decode() if isinstance(value, bytes) else value


class Run:
    """A run's outputs: `summary` (summary.json as a dict), `status`, and every dataset of
    run.h5 by its path (run["vessel/pose_true"]), with its attributes in `attrs[path]`
    ('columns' and 'units') and the file's in `file_attrs`."""

    def __init__(self, data, attrs, file_attrs, summary=None, status="ok", message=""):
        self.data = data
        self.attrs = attrs
        self.file_attrs = file_attrs
        self.summary = summary or {}
        self.status = status
        self.message = message

    def __getitem__(self, path):
        return self.data[path]

    def __contains__(self, path):
        return path in self.data

    def keys(self):
        return self.data.keys()

    @property
    def time(self):
        return self.data["time"]

    def columns(self, path):
        """The names of a dataset's columns, as run.h5 declares them."""
        return _text(self.attrs[path].get("columns", "")).split(",")

    def to_xarray(self):
        """The time series as an xarray Dataset: one variable per dataset whose first axis
        is the output time, its columns a named dimension, its units an attribute."""
        import xarray as xr

        n = len(self.time)
        variables = {}
        for path, values in self.data.items():
            if path == "time" or values.ndim == 0 or values.shape[0] != n:
                continue
            name = path.replace("/", ".")
            attrs = {"units": _text(self.attrs[path].get("units", ""))}
            if values.ndim == 1:
                variables[name] = xr.Variable(("time",), values, attrs)
            else:
                dim = f"{name}.column"
                variables[name] = (("time", dim), values, attrs)
                if "columns" in self.attrs[path]:
                    variables[dim] = ((dim,), self.columns(path))
        ds = xr.Dataset(variables, coords={"time": ("time", self.time, {"units": "s"})})
        ds.attrs.update({k: _text(v) if isinstance(v, bytes) else v
                         for k, v in self.file_attrs.items()})
        return ds


def _check_layout(path, data):
    """Every table of run.h5 (or detect.h5) that moorsim declares has its declared shape:
    a series one-dimensional, a table its columns (per line: as many as the anchors)."""
    lines = data["mooring/anchors"].shape[0] if "mooring/anchors" in data else None
    for table, width, _units, _columns in _moorsim._layout():
        if table.startswith("/"):
            names = [table[1:]]
        else:  # a detector's table, under detectors/<label>/
            names = [k for k in data if k.startswith("detectors/") and k.endswith("/" + table)]
        for name in names:
            if name not in data:
                continue
            shape = data[name].shape
            if width == 0:
                good, wanted = len(shape) == 1, "(rows,)"
            elif width == -1:
                good = len(shape) == 2 and (lines is None or shape[1] == lines)
                wanted = f"(rows, {lines if lines is not None else 'lines'})"
            elif width == -2:
                good, wanted = len(shape) == 2, "(rows, hypotheses)"
            else:
                good, wanted = len(shape) == 2 and shape[1] == width, f"(rows, {width})"
            if not good:
                raise InputError(f"{path}: /{name}: shape {shape}, expected {wanted}")


def read_run(directory_or_file):
    """A run's outputs from its directory (run.h5 and summary.json) or from a run.h5."""
    import h5py

    path = directory_or_file
    if os.path.isdir(path):
        path = os.path.join(path, "run.h5")
    data, attrs = {}, {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset):
                data[name] = obj[()]
                attrs[name] = dict(obj.attrs)
        f.visititems(visit)
        file_attrs = dict(f.attrs)
    _check_layout(path, data)
    summary_path = os.path.join(os.path.dirname(path), "summary.json")
    summary = {}
    if os.path.exists(summary_path):
        with open(summary_path) as s:
            summary = json.load(s)
    return Run(data, attrs, file_attrs, summary, summary.get("status", "ok"))


def run(scenario, seed=None, duration=None, set=None, out=None):
    """Runs a scenario as `moorsim run` does and returns its Run. `set` overrides scenario
    values ({"environment.waves.hs": 4}); `out` keeps run.h5 and summary.json in that
    directory (without it they are written to a temporary one and read back). A rejected
    scenario raises InputError; a run that failed returns with status "failed" and its
    message. Ctrl-C stops it (KeyboardInterrupt)."""
    directory = out or tempfile.mkdtemp(prefix="moorsim-run-")
    try:
        result = _moorsim._run(str(scenario), _overrides(set, seed, duration), str(directory))
        if result["status"] == "rejected":
            raise InputError(result["message"])
        summary = json.loads(result["summary"]) if result["summary"] else {}
        if os.path.exists(os.path.join(directory, "run.h5")):
            r = read_run(directory)
        else:
            r = Run({}, {}, {}, summary)
        r.summary, r.status, r.message = summary, result["status"], result["message"]
        return r
    finally:
        if out is None:
            shutil.rmtree(directory, ignore_errors=True)


def read_campaign(directory):
    """A campaign's table (DIR/runs.csv) as a pandas DataFrame, one row per run; its
    campaign.json (what was run) in `.attrs["campaign"]`."""
    import pandas as pd

    table = pd.read_csv(os.path.join(directory, "runs.csv"), comment="#")
    campaign = os.path.join(directory, "campaign.json")
    if os.path.exists(campaign):
        with open(campaign) as f:
            table.attrs["campaign"] = json.load(f)
    return table


def read_design(directory):
    """A design campaign's checks (`moorsim batch` of a campaign with a `design` section):
    {"extremes": DataFrame (DIR/design.csv: per block, point and line the MPM with its
    interval, the design tension, safety factor, utilisation and result), "offsets":
    DataFrame (per block and point the largest offset's MPM against the limit), "fatigue":
    DataFrame (DIR/fatigue.csv: per line and place the damage per year and the life),
    "checks": DIR/design.json as read}. Raises FileNotFoundError naming design.json for a
    campaign without design checks."""
    import pandas as pd

    path = os.path.join(directory, "design.json")
    if not os.path.exists(path):
        raise FileNotFoundError(f"{path}: no design checks (the campaign has no design section)")
    with open(path) as f:
        checks = json.load(f)
    offsets = pd.DataFrame([
        {"block": o["block"], "point": o["point"], "condition": o["condition"], "runs": o["runs"],
         "method": o.get("method"), "mpm": (o.get("mpm") or {}).get("value"), "mpm_lower": (o.get("mpm") or {}).get("lower"),
         "mpm_upper": (o.get("mpm") or {}).get("upper"), "limit": o.get("limit"),
         "pass": o.get("pass")}
        for o in checks["offsets"]])
    return {"extremes": pd.read_csv(os.path.join(directory, "design.csv")),
            "offsets": offsets,
            "fatigue": pd.read_csv(os.path.join(directory, "fatigue.csv")),
            "checks": checks}


def run_campaign(campaign, out=None, threads=0, keep_runs=False, progress=False):
    """Runs (or resumes) a campaign as `moorsim batch` does, on `threads` threads (0: every
    core), and returns its table (read_campaign). A campaign refused before its first run
    raises InputError; runs that failed are rows with their status."""
    result = _moorsim._run_campaign(str(campaign), None if out is None else str(out),
                                    int(threads), bool(keep_runs), bool(progress))
    if result["status"] == "rejected":
        raise InputError(result["message"])
    if result["status"] == "failed":
        raise Error(result["message"])
    return read_campaign(result["directory"])


def detect(scenario, time, pose, thrust=None, tensions=None, set=None):
    """The scenario's detectors on recorded samples, as `moorsim detect` runs them: `time`
    (n,), `pose` (n, 3) measured x, y [m] and heading [rad] (NaN where a channel delivered
    nothing), `thrust` (n, 3) the thrust issued X, Y [N], N [N m] (zeros without it),
    `tensions` (n, lines) load-cell readings [N] where fitted. Returns {"detectors": {label:
    {"type", "alarm", "decision", "score"}}, "hypotheses": [...], "summary": {...}}."""
    time = np.ascontiguousarray(time, dtype=float)
    pose = np.ascontiguousarray(pose, dtype=float)
    thrust = None if thrust is None else np.ascontiguousarray(thrust, dtype=float)
    tensions = None if tensions is None else np.ascontiguousarray(tensions, dtype=float)
    result = _moorsim._detect(str(scenario), _overrides(set), time, pose, thrust, tensions)
    result["summary"] = json.loads(result["summary"])
    for verdicts in result["detectors"].values():
        verdicts["alarm"] = verdicts["alarm"].astype(bool)
        verdicts["decision"] = verdicts["decision"].astype(int)
    return result
