#!/usr/bin/python3
"""Draws a scenario's mooring at rest: plan view and every line's profile.

    python3 tools/plot_mooring.py SCENARIO [--out FILE.png] [--set key.path=value]...

The lines are settled to their static rest with the vessel at its initial pose (the same
solve `moorsim static` and the start of every run make), through the Python API. Left:
the lines seen from above (north up, east right), the anchors numbered. Right: each line's
profile, depth against the horizontal distance from its anchor, coloured by the tension in
each segment, so chain, rope, clump weights and buoys show where the tension changes.
Default output: the scenario's name with .png, in the current folder.

Needs the moorsim Python package (`tools/main.sh` installs it) and Debian's python3-numpy
and python3-matplotlib; if `python3` on PATH is not Debian's, run /usr/bin/python3.
A scenario that does not load ends the script with its one-line message and exit code 2.
"""

import argparse
import sys
from pathlib import Path

try:
    import matplotlib
    import numpy as np
    import moorsim
except ImportError as error:
    print(f"plot_mooring: python module '{error.name}' is missing: install python3-numpy "
          f"python3-matplotlib (tools/setup.sh) and moorsim's package (tools/main.sh), "
          f"and use /usr/bin/python3", file=sys.stderr)
    sys.exit(1)

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402 (after the backend is chosen)
from matplotlib.collections import LineCollection  # noqa: E402

EXIT_BAD_INPUT = 2


def settled_lines(scenario: str, overrides: list[str]):
    """Node positions (NED, z down) and segment tensions of every line at rest."""
    lines = moorsim.Lines(scenario, overrides)
    lines.init(np.zeros(6), np.zeros(6))
    return [(lines.node_positions(k), lines.segment_tensions(k))
            for k in range(1, lines.num_lines + 1)]


def draw_plan(ax, shapes):
    for k, (nodes, _) in enumerate(shapes, start=1):
        ax.plot(nodes[:, 1], nodes[:, 0], color="tab:blue", lw=1.0)
        ax.plot(nodes[0, 1], nodes[0, 0], "^", color="k", ms=6)
        ax.annotate(str(k), (nodes[0, 1], nodes[0, 0]), xytext=(5, 5),
                    textcoords="offset points", fontsize=9)
    fairleads = np.array([nodes[-1] for nodes, _ in shapes])
    ax.plot(fairleads[:, 1], fairleads[:, 0], "o", color="tab:red", ms=3, label="fairleads")
    ax.plot([], [], "^", color="k", label="anchors")
    ax.set_aspect("equal")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("plan view, lines at rest", fontsize=10)


def draw_profiles(fig, ax, shapes):
    segments, tensions = [], []
    for nodes, tension in shapes:
        distance = np.hypot(nodes[:, 0] - nodes[0, 0], nodes[:, 1] - nodes[0, 1])
        points = np.column_stack([distance, nodes[:, 2]])
        segments += [points[i:i + 2] for i in range(len(points) - 1)]
        tensions += list(tension / 1e6)
    collection = LineCollection(segments, array=np.array(tensions), cmap="viridis", lw=2.0)
    ax.add_collection(collection)
    ax.autoscale()
    ax.invert_yaxis()
    ax.set_xlabel("horizontal distance from the anchor [m]")
    ax.set_ylabel("depth [m]")
    fig.colorbar(collection, ax=ax, label="segment tension [MN]")
    ax.set_title("profiles of all lines", fontsize=10)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description="Draw a scenario's mooring at rest.")
    parser.add_argument("scenario", help="scenario YAML file")
    parser.add_argument("--out", type=Path, help="PNG to write (default: NAME.png)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="scenario override, as for `moorsim run --set`")
    args = parser.parse_args(argv)
    try:
        shapes = settled_lines(args.scenario, args.set)
    except moorsim.InputError as error:
        print(f"plot_mooring: {error}", file=sys.stderr)
        return EXIT_BAD_INPUT
    out = args.out if args.out is not None else Path(Path(args.scenario).stem + ".png")
    fig, (plan, profile) = plt.subplots(1, 2, figsize=(12, 4.8),
                                        gridspec_kw={"width_ratios": [1, 1.4]})
    draw_plan(plan, shapes)
    draw_profiles(fig, profile, shapes)
    fig.suptitle(f"{Path(args.scenario).name}: {len(shapes)} lines", fontsize=11)
    fig.tight_layout()
    try:
        fig.savefig(out, dpi=120)
    except OSError as error:
        print(f"plot_mooring: cannot write {out}: {error.strerror}", file=sys.stderr)
        return EXIT_BAD_INPUT
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
