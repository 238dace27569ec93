#!/usr/bin/python3
"""Plots one moorsim run: reads RUN_DIR/run.h5 and writes PNG figures.

    python3 tools/plot_run.py RUN_DIR [--out DIR] [--show]

RUN_DIR may also be the --out directory of `moorsim detect` (detect.h5: the detectors on
a recorded stream, without the plant): the figures are then the measured ones only
(no true pose, no tensions, the thrust as the stream gave it).

Figures (in --out, default RUN_DIR):
  trajectory.png  north-east track, true and measured, with rays toward the anchors
  pose.png        x, y and heading against time, true and measured
  tensions.png    fairlead tension of every line
  thrust.png      commanded and delivered thrust X, Y, N
  detectors.png   decision of each detector against time (only if the run has detectors)
  detector_scores.png  each detector's per-hypothesis scores: DHT probabilities, MLE
                  negative log-likelihoods, GLR statistics

The layout of run.h5 is docs/design.md section 7 (SI units, NED Earth frame: x north, y east,
heading psi from north towards east). A missing file or required dataset ends the script
with a one-line error and exit code 2.

Needs Debian's python3-numpy, python3-h5py and python3-matplotlib (tools/setup.sh); if
`python3` on PATH is not Debian's, run /usr/bin/python3.
"""

import argparse
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path

try:
    import h5py
    import matplotlib
    import numpy as np
except ImportError as error:
    print(f"plot_run: python module '{error.name}' is missing: install python3-numpy "
          f"python3-h5py python3-matplotlib (tools/setup.sh) and use /usr/bin/python3",
          file=sys.stderr)
    sys.exit(1)

EXIT_BAD_INPUT = 2
FAILURE_COLOUR = "tab:red"


class RunFileError(Exception):
    """run.h5 is missing or lacks something the plots need."""


@dataclass
class Detector:
    decision: np.ndarray  # (N,) 0 = intact, k = line k
    alarm: np.ndarray | None  # (N,) 0/1
    score: np.ndarray | None = None  # (N, hypotheses): probability, NLL or statistic
    kind: str = ""  # detector type (dht, mle, glr)
    hypotheses: list[str] = field(default_factory=list)
    threshold: float | None = None  # the alarm rule's threshold on the score, if it has one


@dataclass
class Run:
    title: str
    time: np.ndarray  # (N,) s
    pose_true: np.ndarray | None  # (N, 6) x, y, z m; phi, theta, psi rad (NED); None: detect.h5
    pose_measured: np.ndarray  # (N, 3) x, y m; psi rad; NaN where missing
    fairlead_tension: np.ndarray | None  # (N, lines) N; None: detect.h5
    thrust_commanded: np.ndarray | None  # (N, 3) X, Y N; N N m (body); None: detect.h5
    thrust_delivered: np.ndarray  # (N, 3)
    anchors: np.ndarray | None  # (lines, 3) m (NED)
    failure_line: int  # 1-based, 0 = no failure
    failure_time: float  # s, NaN = no failure
    detectors: dict[str, Detector] = field(default_factory=dict)

    @property
    def lines(self) -> int:
        """Mooring lines: the tension columns, else the single-line hypotheses."""
        if self.fairlead_tension is not None:
            return self.fairlead_tension.shape[1]
        labels = next((d.hypotheses for d in self.detectors.values()), [])
        return sum(1 for label in labels if label.startswith("line "))

    @property
    def has_failure(self) -> bool:
        return self.failure_line > 0 and math.isfinite(self.failure_time)


# ---------------------------------------------------------------------------- reading


def attribute_text(value) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray) and value.size == 1:
        return attribute_text(value.item())
    return str(value)


def read_table(h5: h5py.File, path: str, columns: int | None, rows: int | None) -> np.ndarray:
    """The dataset at `path`: one-dimensional if `columns` is None, else two-dimensional
    with `columns` columns (0: any number). `rows`, if given, is the required length."""
    if path not in h5 or not isinstance(h5[path], h5py.Dataset):
        raise RunFileError(f"{h5.filename}: missing dataset {path}")
    data = h5[path][()]
    expected_ndim = 1 if columns is None else 2
    if data.ndim != expected_ndim or (data.ndim == 2 and columns and data.shape[1] != columns):
        wanted = "(N,)" if columns is None else f"(N, {columns if columns > 0 else 'k'})"
        raise RunFileError(f"{h5.filename}: {path} has shape {data.shape}, expected {wanted}")
    if rows is not None and data.shape[0] != rows:
        raise RunFileError(f"{h5.filename}: {path} has {data.shape[0]} rows, /time has {rows}")
    return data


def read_detectors(h5: h5py.File, rows: int) -> dict[str, Detector]:
    detectors = {}
    group = h5.get("detectors")
    if not isinstance(group, h5py.Group):
        return detectors
    for name in sorted(group):
        if not isinstance(group[name], h5py.Group) or "decision" not in group[name]:
            continue
        base = f"/detectors/{name}"
        alarm = read_table(h5, f"{base}/alarm", None, rows) if "alarm" in group[name] else None
        score = None
        if "score" in group[name] and group[name]["score"].ndim == 2:
            score = read_table(h5, f"{base}/score", group[name]["score"].shape[1], rows)
        kind = attribute_text(group[name].attrs.get("type", ""))
        labels = attribute_text(group.attrs.get("hypotheses", ""))
        hypotheses = labels.split(",") if labels else []
        threshold = group[name].attrs.get("threshold")
        detectors[name] = Detector(read_table(h5, f"{base}/decision", None, rows), alarm, score,
                                   kind, hypotheses,
                                   float(threshold) if threshold is not None else None)
    return detectors


def read_run(path: Path) -> Run:
    if not path.is_file():
        raise RunFileError(f"{path}: no such file")
    try:
        h5 = h5py.File(path, "r")
    except OSError as error:
        raise RunFileError(f"{path}: not a readable HDF5 file ({error})") from None
    with h5:
        time = read_table(h5, "/time", None, None)
        rows = time.shape[0]
        anchors = None
        if "/mooring/anchors" in h5:
            anchors = read_table(h5, "/mooring/anchors", 3, None)
        name = attribute_text(h5.attrs.get("scenario_name", "unnamed scenario"))
        seed = attribute_text(h5.attrs.get("seed", "?"))
        # detect.h5 (moorsim detect) has what a recorded stream gives, no plant.
        detect = "input" in h5.attrs
        title = (f"{name}, detection on {attribute_text(h5.attrs['input'])}" if detect
                 else f"{name}, seed {seed}")
        return Run(
            title=title,
            time=time,
            pose_true=None if detect else read_table(h5, "/vessel/pose_true", 6, rows),
            pose_measured=read_table(h5, "/vessel/pose_measured", 3, rows),
            fairlead_tension=(None if detect
                              else read_table(h5, "/mooring/fairlead_tension", 0, rows)),
            thrust_commanded=None if detect else read_table(h5, "/thrust/commanded", 3, rows),
            thrust_delivered=read_table(h5, "/thrust/delivered", 3, rows),
            anchors=anchors,
            failure_line=int(h5.attrs.get("failure_line", 0)),
            failure_time=float(h5.attrs.get("failure_time", math.nan)),
            detectors=read_detectors(h5, rows),
        )


# ---------------------------------------------------------------------------- helpers


def unwrap_ignoring_nan(angle: np.ndarray) -> np.ndarray:
    """np.unwrap over the finite samples only (one NaN would spoil all that follow)."""
    result = angle.astype(float)
    finite = np.isfinite(result)
    result[finite] = np.unwrap(result[finite])
    return result


def heading_degrees(run: Run) -> tuple[np.ndarray, np.ndarray]:
    """True and measured heading in degrees, the measured one on the true one's branch
    (sensors report psi wrapped, the simulation's psi is continuous). Without the true
    pose (detect.h5) the measured one unwrapped, for both."""
    if run.pose_true is None:
        measured = np.degrees(unwrap_ignoring_nan(run.pose_measured[:, 2]))
        return measured, measured
    true = unwrap_ignoring_nan(run.pose_true[:, 5])
    measured = run.pose_measured[:, 2]
    measured = true + np.angle(np.exp(1j * (measured - true)))
    return np.degrees(true), np.degrees(measured)


def mark_failure(run: Run, axes) -> None:
    if not run.has_failure:
        return
    for ax in np.atleast_1d(axes):
        ax.axvline(run.failure_time, color=FAILURE_COLOUR, linestyle="--", linewidth=1.0,
                   label=f"line {run.failure_line} fails")


def new_figure(plt, run: Run, what: str, rows: int = 1, height: float = 4.0):
    figure, axes = plt.subplots(rows, 1, sharex=True, figsize=(9.0, height), squeeze=False,
                                layout="constrained")
    figure.suptitle(f"{what}: {run.title}")
    return figure, axes[:, 0]


def save(figure, out_dir: Path, name: str) -> Path:
    path = out_dir / name
    figure.savefig(path, dpi=120)
    print(f"wrote {path}")
    return path


# ---------------------------------------------------------------------------- figures


def plot_trajectory(plt, run: Run, out_dir: Path) -> Path:
    figure, (ax,) = new_figure(plt, run, "Trajectory", height=8.0)
    track = run.pose_true if run.pose_true is not None else run.pose_measured
    north, east = track[:, 0], track[:, 1]
    ax.plot(run.pose_measured[:, 1], run.pose_measured[:, 0], ".", markersize=1.5,
            color="tab:orange", alpha=0.5, label="measured")
    if run.pose_true is not None:
        ax.plot(east, north, color="tab:blue", linewidth=1.0, label="true")
    if len(run.time) > 0:
        ax.plot(east[0], north[0], "o", color="black", label="start")
        if run.has_failure:
            at_east = np.interp(run.failure_time, run.time, east)
            at_north = np.interp(run.failure_time, run.time, north)
            ax.plot(at_east, at_north, "X", color=FAILURE_COLOUR, markersize=9,
                    label=f"line {run.failure_line} fails (t = {run.failure_time:g} s)")
        if run.anchors is not None:
            draw_anchor_rays(ax, run, east, north)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.grid(True, linewidth=0.3)
    ax.legend(loc="best", fontsize="small")
    return save(figure, out_dir, "trajectory.png")


def draw_anchor_rays(ax, run: Run, east: np.ndarray, north: np.ndarray) -> None:
    """Arrows around the track pointing toward each line's anchor. The anchors lie
    kilometres away and the vessel moves metres, so the arrows show directions only; they
    start outside the track so as not to hide it."""
    finite = np.isfinite(east) & np.isfinite(north)
    if not finite.any():
        return
    centre = np.array([(east[finite].min() + east[finite].max()) / 2,
                       (north[finite].min() + north[finite].max()) / 2])
    radius = max(np.hypot(east[finite] - centre[0], north[finite] - centre[1]).max(), 1.0)
    for index, (anchor_north, anchor_east, _) in enumerate(run.anchors):
        direction = np.array([anchor_east, anchor_north]) - centre
        norm = np.hypot(*direction)
        if norm == 0.0 or not np.isfinite(norm):
            continue
        direction /= norm
        line = index + 1
        failed = run.has_failure and line == run.failure_line
        colour = FAILURE_COLOUR if failed else "dimgrey"
        base = centre + 1.05 * radius * direction
        tip = centre + 1.35 * radius * direction
        label = centre + 1.45 * radius * direction
        ax.annotate("", xy=tip, xytext=base,
                    arrowprops={"arrowstyle": "->", "color": colour,
                                "linewidth": 1.6 if failed else 0.8})
        ax.plot(*np.column_stack([base, label]), alpha=0.0)  # autoscale to the arrows
        ax.text(*label, str(line), color=colour, ha="center", va="center", fontsize="small",
                fontweight="bold" if failed else "normal")


def plot_pose(plt, run: Run, out_dir: Path) -> Path:
    figure, axes = new_figure(plt, run, "Position and heading", rows=3, height=8.0)
    heading_true, heading_measured = heading_degrees(run)
    track = run.pose_true if run.pose_true is not None else run.pose_measured
    channels = [
        ("x (north) [m]", track[:, 0], run.pose_measured[:, 0]),
        ("y (east) [m]", track[:, 1], run.pose_measured[:, 1]),
        ("heading [deg]", heading_true, heading_measured),
    ]
    for ax, (label, true, measured) in zip(axes, channels):
        ax.plot(run.time, measured, color="tab:orange", linewidth=0.6, alpha=0.7,
                label="measured")
        if run.pose_true is not None:
            ax.plot(run.time, true, color="tab:blue", linewidth=1.0, label="true")
        ax.set_ylabel(label)
        ax.grid(True, linewidth=0.3)
    mark_failure(run, axes)
    axes[0].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel("time [s]")
    return save(figure, out_dir, "pose.png")


def plot_tensions(plt, run: Run, out_dir: Path) -> Path:
    figure, (ax,) = new_figure(plt, run, "Fairlead tension", height=5.0)
    for index in range(run.fairlead_tension.shape[1]):
        ax.plot(run.time, run.fairlead_tension[:, index] / 1e3, linewidth=0.8,
                label=f"line {index + 1}")
    mark_failure(run, ax)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("tension [kN]")
    ax.grid(True, linewidth=0.3)
    ax.legend(loc="best", fontsize="small", ncol=2)
    return save(figure, out_dir, "tensions.png")


def plot_thrust(plt, run: Run, out_dir: Path) -> Path:
    figure, axes = new_figure(plt, run, "Thrust (body axes)", rows=3, height=8.0)
    channels = [("X [kN]", 1e3), ("Y [kN]", 1e3), ("N [MN m]", 1e6)]
    for column, (ax, (label, scale)) in enumerate(zip(axes, channels)):
        if run.thrust_commanded is not None:
            ax.plot(run.time, run.thrust_commanded[:, column] / scale, color="tab:gray",
                    linestyle="--", linewidth=0.8, label="commanded")
        ax.plot(run.time, run.thrust_delivered[:, column] / scale, color="tab:green",
                linewidth=1.0, label="delivered" if run.pose_true is not None else "as recorded")
        ax.set_ylabel(label)
        ax.grid(True, linewidth=0.3)
    mark_failure(run, axes)
    axes[0].legend(loc="best", fontsize="small")
    axes[-1].set_xlabel("time [s]")
    return save(figure, out_dir, "thrust.png")


def plot_detectors(plt, run: Run, out_dir: Path) -> Path:
    names = sorted(run.detectors)
    figure, axes = new_figure(plt, run, "Detector decisions", rows=len(names),
                              height=1.2 + 2.4 * len(names))
    for ax, name in zip(axes, names):
        detector = run.detectors[name]
        ax.step(run.time, detector.decision, where="post", color="tab:blue", linewidth=1.0,
                label="decision")
        if detector.alarm is not None and len(run.time) > 0:
            ax.fill_between(run.time, 0, 1, where=detector.alarm != 0, step="post",
                            transform=ax.get_xaxis_transform(), color="tab:red", alpha=0.15,
                            linewidth=0, label="alarm")
        if run.has_failure:
            ax.axhline(run.failure_line, color=FAILURE_COLOUR, linestyle=":", linewidth=0.8,
                       label=f"failed line {run.failure_line}")
        lines = max(run.lines, int(np.max(detector.decision, initial=0)))
        ax.set_ylim(-0.5, lines + 0.5)
        ax.yaxis.get_major_locator().set_params(integer=True)
        ax.set_title(name, loc="left", fontsize="medium")
        ax.set_ylabel("line (0 = intact)")
        ax.grid(True, linewidth=0.3)
        ax.legend(loc="upper left", fontsize="small")
    mark_failure(run, axes)
    axes[-1].set_xlabel("time [s]")
    return save(figure, out_dir, "detectors.png")


SCORE_LABELS = {
    "dht": ("hypothesis probability", "log"),
    "mle": ("NLL - intact NLL [nats]", "linear"),
    "glr": ("GLR statistic", "linear"),
}


def plot_scores(plt, run: Run, out_dir: Path) -> Path:
    """Per detector, every hypothesis's score against time (TAPM thesis figures 5.4-5.6)."""
    names = [n for n in sorted(run.detectors) if run.detectors[n].score is not None]
    figure, axes = new_figure(plt, run, "Detector scores", rows=len(names),
                              height=1.2 + 2.6 * len(names))
    for ax, name in zip(axes, names):
        detector = run.detectors[name]
        label, scale = SCORE_LABELS.get(detector.kind, ("score", "linear"))
        score = detector.score
        if detector.kind == "mle":  # the absolute NLLs drift together; their gaps decide
            score = score - score[:, :1]
        for h in range(score.shape[1]):
            text = detector.hypotheses[h] if h < len(detector.hypotheses) else f"hypothesis {h}"
            failed = run.has_failure and text == f"line {run.failure_line}"
            ax.plot(run.time, score[:, h], linewidth=1.6 if failed or h == 0 else 0.7,
                    color="black" if h == 0 else (FAILURE_COLOUR if failed else None),
                    label=text)
        if detector.threshold is not None:
            ax.axhline(detector.threshold, color="tab:red", linestyle="--", linewidth=0.9,
                       label=f"alarm threshold {detector.threshold:g}")
        ax.set_yscale(scale)
        ax.set_title(f"{name} ({detector.kind})", loc="left", fontsize="medium")
        ax.set_ylabel(label)
        ax.grid(True, linewidth=0.3)
        ax.legend(loc="upper left", fontsize="x-small", ncol=3)
    mark_failure(run, axes)
    axes[-1].set_xlabel("time [s]")
    return save(figure, out_dir, "detector_scores.png")


# ---------------------------------------------------------------------------- main


def parse_arguments(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description="Plot a moorsim run (RUN_DIR/run.h5) as PNGs.")
    parser.add_argument("run_dir", type=Path, metavar="RUN_DIR",
                        help="directory holding run.h5 (or detect.h5 of moorsim detect)")
    parser.add_argument("--out", type=Path, metavar="DIR", help="where to write (default RUN_DIR)")
    parser.add_argument("--show", action="store_true", help="also open the figures in a window")
    return parser.parse_args(argv)


def main(argv: list[str]) -> int:
    args = parse_arguments(argv)
    if not args.show:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # after choosing the backend

    try:
        run_file = args.run_dir / "run.h5"
        if not run_file.is_file() and (args.run_dir / "detect.h5").is_file():
            run_file = args.run_dir / "detect.h5"
        run = read_run(run_file)
    except RunFileError as error:
        print(f"plot_run: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    out_dir = args.out if args.out is not None else args.run_dir
    out_dir.mkdir(parents=True, exist_ok=True)

    figures = [plot_trajectory, plot_pose, plot_thrust]
    if run.fairlead_tension is not None:
        figures.insert(2, plot_tensions)
    if run.detectors:
        figures.append(plot_detectors)
        if any(d.score is not None for d in run.detectors.values()):
            figures.append(plot_scores)
    for plot in figures:
        plot(plt, run, out_dir)
        if not args.show:
            plt.close("all")  # free each figure once saved
    if args.show:
        plt.show()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
