#!/usr/bin/python3
"""Draws the MoorDyn side-by-side benchmark as one figure.

    KEEP=1 benchmarks/moordyn_side_by_side.sh MOORDYN MOORSIM   # prints its work folder
    python3 benchmarks/plot_moordyn_side_by_side.py WORK_FOLDER OUT.png

Left: for each setting the benchmark timed, the wall time of a 600 s run against its error
(the worst line's RMS fairlead-tension difference from its own program's reference, % of
the reference's range), both moorings. Right: the composite mooring's line whose tension
varies most, over three heave periods (the fairleads surge 5 m with a 100 s period and
heave 2 m with a 12 s period): both references, moorsim at its default settings and
MoorDyn at its usual scheme (RK2, 2 ms), and below, each one's difference from MoorDyn's
reference.

Reads WORK_FOLDER/results.csv (one row per setting, written by the benchmark) and the
tension CSVs it names. Needs Debian's python3-numpy and python3-matplotlib.
"""

import csv
import sys
from pathlib import Path

try:
    import matplotlib
    import numpy as np
except ImportError as error:
    print(f"plot_moordyn_side_by_side: python module '{error.name}' is missing: install "
          f"python3-numpy python3-matplotlib (tools/setup.sh) and use /usr/bin/python3",
          file=sys.stderr)
    sys.exit(1)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after the backend is chosen)

EXIT_BAD_INPUT = 2
PROGRAM_STYLE = {"moorsim": ("tab:blue", "o"), "MoorDyn": ("tab:orange", "s")}
MODEL_LABEL = {"seed": "eight chains", "composite": "chain-polyester-chain with clump weights"}
WINDOW = (200.0, 236.0)  # s: three heave periods
Y_LIMITS = (0.02, 10.0)  # % of range
USUAL_MOORDYN = "RK2 dtM 0.002 s"


def read_tensions(path):
    """time (N,) and tensions (N, lines) of a benchmark CSV ('#' comments, a header row)."""
    rows = [line for line in path.read_text().splitlines()
            if line and not line.startswith("#") and not line.startswith("time")]
    if not rows:
        raise ValueError(f"{path}: no rows")
    data = np.array([[float(v) for v in row.split(",")] for row in rows])
    return data[:, 0], data[:, 1:]


def read_results(folder):
    path = folder / "results.csv"
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path}: no rows")
    return rows


def own_error(row):
    column = "rms_vs_moorsim_ref_pct" if row["program"] == "moorsim" else "rms_vs_moordyn_ref_pct"
    return float(row[column])


def draw_cost(ax, rows):
    fastest = {}  # (model, program) -> the fastest row within 1 % of its own reference
    for row in rows:
        if row["setting"] == "reference" or row["wall_s"] in ("", "-"):
            continue
        colour, marker = PROGRAM_STYLE[row["program"]]
        wall, error = float(row["wall_s"]), own_error(row)
        if error > Y_LIMITS[1]:  # a setting that ran but diverged: drawn at the top edge
            ax.annotate(f"{row['setting']}: diverged", (wall, Y_LIMITS[1]), fontsize=7,
                        xytext=(0, -12), textcoords="offset points", ha="center",
                        color=colour, arrowprops={"arrowstyle": "->", "color": colour})
            continue
        ax.plot(wall, max(error, Y_LIMITS[0]), marker, ms=8, color=colour,
                mfc=colour if row["model"] == "seed" else "white", mew=1.5)
        key = (row["model"], row["program"])
        if error <= 1.0 and (key not in fastest or wall < float(fastest[key]["wall_s"])):
            fastest[key] = row
        if row["program"] == "MoorDyn" and row["setting"] == USUAL_MOORDYN:
            fastest[key + ("usual",)] = row
    for row in fastest.values():  # name only the settings the text compares
        ax.annotate(row["setting"], (float(row["wall_s"]), own_error(row)), fontsize=7,
                    xytext=(5, 4 if row["model"] == "seed" else -10), textcoords="offset points",
                    color=PROGRAM_STYLE[row["program"]][0])
    ax.axhline(1.0, color="grey", lw=0.8, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(*Y_LIMITS)
    ax.set_xlabel("wall time of a 600 s run, one core [s]")
    ax.set_ylabel("error against its own reference [% of range]")
    handles = [plt.Line2D([], [], color=c, marker=m, ls="", label=p)
               for p, (c, m) in PROGRAM_STYLE.items()]
    handles += [plt.Line2D([], [], color="k", marker="o", ls="", label=MODEL_LABEL["seed"]),
                plt.Line2D([], [], color="k", marker="o", mfc="white", ls="",
                           label=MODEL_LABEL["composite"])]
    ax.legend(handles=handles, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13),
              ncol=4)
    ax.set_title("each setting's cost and accuracy (named: the fastest within 1 %,\n"
                 "and MoorDyn's usual RK2 at 2 ms)", fontsize=9)


def draw_tensions(top, bottom, rows, folder):
    composite = {(r["program"], r["setting"]): r for r in rows if r["model"] == "composite"}
    curves = [(("moorsim", "reference"), "moorsim reference (rtol 1e-7)", "tab:blue", "-", 1.2),
              (("moorsim", "rtol 0.0001"), "moorsim default (rtol 1e-4)", "k", "--", 1.0),
              (("MoorDyn", USUAL_MOORDYN), "MoorDyn RK2, 2 ms", "tab:red", ":", 1.5)]
    t_ref, f_ref = read_tensions(folder / composite[("MoorDyn", "reference")]["csv"])
    in_window = (t_ref >= WINDOW[0]) & (t_ref <= WINDOW[1])
    line = int(np.argmax(np.ptp(f_ref[in_window], axis=0)))
    reference = dict(zip(np.round(t_ref, 3), f_ref[:, line]))
    top.plot(t_ref[in_window], f_ref[in_window, line] / 1e6, color="tab:orange", lw=2.5,
             label="MoorDyn reference (RK4, 1 ms)")
    for key, label, colour, style, width in curves:
        if key not in composite or not (folder / composite[key]["csv"]).is_file():
            continue
        t, f = read_tensions(folder / composite[key]["csv"])
        keep = (t >= WINDOW[0]) & (t <= WINDOW[1])
        top.plot(t[keep], f[keep, line] / 1e6, style, color=colour, lw=width, label=label)
        difference = [f[i, line] - reference[round(t[i], 3)] for i in np.flatnonzero(keep)]
        bottom.plot(t[keep], np.array(difference) / 1e3, style, color=colour, lw=width)
    top.set_ylabel(f"line {line + 1} tension [MN]")
    top.legend(fontsize=7)
    top.set_title(f"composite mooring, line {line + 1}'s fairlead tension", fontsize=9)
    bottom.axhline(0.0, color="tab:orange", lw=1.0)
    bottom.set_xlabel("time [s]")
    bottom.set_ylabel("minus MoorDyn's\nreference [kN]")


def main(argv):
    if len(argv) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return EXIT_BAD_INPUT
    folder, out = Path(argv[1]), Path(argv[2])
    try:
        rows = read_results(folder)
        fig = plt.figure(figsize=(11, 5.0))
        grid = fig.add_gridspec(3, 2)
        draw_cost(fig.add_subplot(grid[:, 0]), rows)
        top = fig.add_subplot(grid[:2, 1])
        draw_tensions(top, fig.add_subplot(grid[2, 1], sharex=top), rows, folder)
    except (OSError, KeyError, ValueError) as error:
        print(f"plot_moordyn_side_by_side: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
