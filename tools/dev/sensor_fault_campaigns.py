#!/usr/bin/env python3
"""Writes the sensor-fault campaigns (training and held-out) from one description, so that
the two differ in their seed and header alone. Run from the repository root:
    tools/dev/sensor_fault_campaigns.py
A training-side campaign on one question (see focus_campaign), to a file of your choice:
    tools/dev/sensor_fault_campaigns.py --focus noisy_onset|cell_faults_hs6|gnss_outage OUT.yaml
"""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CELLS = (ROOT / "scenarios/campaigns/training/detection_cells_training.yaml").read_text()
# The turret-forward set-up of the cells campaigns: its mooring and turret keys.
SETUP = [l for l in CELLS.splitlines()
         if l.startswith('  "mooring.lines[') or l.startswith("  vessel.turret.")]

HEADING = """      - {key: "environment.current.profile[1].speed", values: [0, 0.5]}
      - {key: environment.waves.direction_toward_deg, uniform: [0, 360]}
      - {key: controller.setpoint.heading_deg, follows: environment.waves.direction_toward_deg, add: [165, 195], modulo: 360}
      - {key: vessel.initial_pose.heading_deg, follows: controller.setpoint.heading_deg}
      - {key: controller.setpoint.x, follows: controller.setpoint.heading_deg, function: cos, scale: -60, add: 60}
      - {key: controller.setpoint.y, follows: controller.setpoint.heading_deg, function: sin, scale: -60}
      - {key: vessel.initial_pose.x, follows: controller.setpoint.x}
      - {key: vessel.initial_pose.y, follows: controller.setpoint.y}
      - {key: environment.current.direction_deg, choice: [0, 45, 90, 135, 180, 225, 270, 315]}"""
SEA = """      - {key: environment.waves.hs, values: [2.5, 4, 6]}
      - {key: environment.waves.tp, follows: environment.waves.hs, add: 4.5}"""

# (block name, sensor key, fault mode, the size key and its draw)
FAULTS = [
    ("gnss_step", "gnss", "step", "offset", "uniform: [1, 5]"),
    ("gnss_frozen", "gnss", "stuck", None, None),
    ("gnss_noisy", "gnss", "degraded", "factor", "uniform: [3, 10]"),
    ("gnss_drift", "gnss", "drift", "rate", "uniform: [0.002, 0.01]"),
    ("gnss_dead", "gnss", "dead", None, None),
    ("gnss_gain", "gnss", "gain", "gain", "uniform: [0.97, 1.03]"),
    ("gyro_step", "gyro", "step", "offset", "uniform: [0.1, 0.3]"),
    ("gyro_frozen", "gyro", "stuck", None, None),
    ("gyro_noisy", "gyro", "degraded", "factor", "uniform: [3, 10]"),
    ("gyro_drift", "gyro", "drift", "rate", "uniform: [2.0e-4, 1.0e-3]"),
    ("gyro_dead", "gyro", "dead", None, None),
    ("cell_step", "tension_cells", "step", "offset", "uniform: [-3.0e6, -1.0e6]"),
    ("cell_stuck", "tension_cells", "stuck", None, None),
    ("cell_noisy", "tension_cells", "degraded", "factor", "uniform: [3, 10]"),
    ("cell_drift", "tension_cells", "drift", "rate", "uniform: [-20000, -2000]"),
    ("cell_dead", "tension_cells", "dead", None, None),
    ("cell_gain", "tension_cells", "gain", "gain", "uniform: [0.5, 0.8]"),
]


# A failure's scenario keys by the campaign's name for it.
FAILURE_SET = {
    "fairlead": "failure.mode: fairlead",
    "midline": "failure.mode: node, failure.arc_length: 1125",
    "anchor": "failure.mode: anchor",
}


def fault_block(name, sensor, mode, size, draw, failure=None, other_line=False):
    """One fault from 400 to 700 s: on an intact mooring (failure None), or with a line
    failure ("fairlead", "midline" or "anchor") drawn in 200-1000 s."""
    key = f"sensors.{sensor}.faults[1]"
    fault = {"mode": mode, "time": 400, "end": 700}
    if sensor == "tension_cells":
        fault = {"line": 1, **fault}
    if size:
        fault[size] = {"offset": 1, "factor": 2, "rate": 1, "gain": 0.9}[size]
    text = ", ".join(f"{k}: {v}" for k, v in fault.items())
    suffix = ("_other" if other_line else "") + {None: "", "fairlead": "_failure",
                                                  "midline": "_midline", "anchor": "_anchor"}[failure]
    lines = [f"  - name: {name}{suffix}", "    set:"]
    lines.append(f"      simulation.duration: {1200 if failure else 1800}")
    lines.append(f"      sensors.{sensor}.faults: [{{{text}}}]")
    if failure:
        lines += [f"      {k}" for k in FAILURE_SET[failure].split(", ")]
    lines.append("    factors:")
    lines.append(SEA)
    if size:
        lines.append(f'      - {{key: "{key}.{size}", {draw}}}')
    if failure:
        # Before (200-400 s), during (400-700 s) or after (700-1000 s) the fault.
        lines.append("      - {key: failure.line, choice: [1, 2, 3, 4, 5, 6, 7, 8]}")
        lines.append("      - {key: failure.time, uniform: [200, 1000]}")
        if sensor == "tension_cells" and not other_line:
            lines.append(f'      - {{key: "{key}.line", follows: failure.line}}')
        elif sensor == "tension_cells":
            lines.append(f'      - {{key: "{key}.line", choice: [1, 2, 3, 4, 5, 6, 7, 8]}}')
    elif sensor == "tension_cells":
        lines.append(f'      - {{key: "{key}.line", choice: [1, 2, 3, 4, 5, 6, 7, 8]}}')
    lines.append(HEADING)
    lines.append("    seeds: 2")
    return "\n".join(lines)


def failure_block(name):
    return "\n".join([
        f"  - name: {name}",
        f"    set: {{simulation.duration: 900, {FAILURE_SET[name]}}}",
        "    factors:",
        SEA,
        "      - {key: failure.line, choice: [1, 2, 3, 4, 5, 6, 7, 8]}",
        "      - {key: failure.time, uniform: [200, 600]}",
        HEADING,
        "    seeds: 8",
    ])


def preamble(name, seed, header):
    """The header, the base scenario, the set-up, the cells and the six detectors."""
    body = [header.rstrip(), f"name: {name}", "scenario: ../library/thesis_no_failure_current.yaml",
            f"seed: {seed}", "set:"]
    body += SETUP
    body += ["  sensors.tension_cells: {rate_hz: 1, noise: {std_dev: 1.0e4}}", "  detectors:"]
    body += [f"    - {{type: {d}}}" for d in ("fused", "cells", "deficit", "dht", "glr", "mle")]
    return body + ["blocks:"]


def campaign(name, seed, header):
    body = preamble(name, seed, header)
    for failure in FAILURE_SET:
        body.append(failure_block(failure))
    body.append("\n".join(["  - name: intact", "    set: {simulation.duration: 3600}",
                           "    factors:", SEA, HEADING, "    seeds: 4"]))
    for f in FAULTS:
        body.append(fault_block(*f))
    for f in FAULTS:
        body.append(fault_block(*f, failure="fairlead"))
    for f in FAULTS:
        if f[1] == "tension_cells":
            body.append(fault_block(*f, failure="fairlead", other_line=True))
    for failure in ("midline", "anchor"):
        for f in FAULTS:
            body.append(fault_block(*f, failure=failure))
    return "\n".join(body) + "\n"


def intact_campaign(name, seed, header, healthy_seeds):
    """Hours on an intact mooring: healthy sensors, and each fault from 300 s to the end of
    an hour (a drift for 600 s: longer, it would carry the reading kilometres away)."""
    body = preamble(name, seed, header)
    body.append("\n".join(["  - name: intact", "    set: {simulation.duration: 3600}",
                           "    factors:", SEA, HEADING, f"    seeds: {healthy_seeds}"]))
    for name_, sensor, mode, size, draw in FAULTS:
        key = f"sensors.{sensor}.faults[1]"
        fault = {"mode": mode, "time": 300}
        if mode == "drift":
            fault["end"] = 900
        if sensor == "tension_cells":
            fault = {"line": 1, **fault}
        if size:
            fault[size] = {"offset": 1, "factor": 2, "rate": 1, "gain": 0.9}[size]
        text = ", ".join(f"{k}: {v}" for k, v in fault.items())
        lines = [f"  - name: {name_}", "    set:", "      simulation.duration: 3600",
                 f"      sensors.{sensor}.faults: [{{{text}}}]", "    factors:", SEA]
        if size:
            lines.append(f'      - {{key: "{key}.{size}", {draw}}}')
        if sensor == "tension_cells":
            lines.append(f'      - {{key: "{key}.line", choice: [1, 2, 3, 4, 5, 6, 7, 8]}}')
        lines += [HEADING, "    seeds: 1"]
        body.append("\n".join(lines))
    return "\n".join(body) + "\n"


COMMON = """# Every sensor fault the simulator models, on every sensor, against the detectors with the
# observers' sensor checks (on with the fused detector): the turret-forward mooring of the
# load-cell campaigns, waves of Hs 2.5, 4 and 6 m (Tp = Hs + 4.5 s) from a heading drawn
# over the compass, the current none or 0.5 m/s, a load cell on every fairlead (1 Hz, 10 kN
# noise). Six detectors in every run: fused, cells, the pose-only force-deficit test, DHT,
# GLR and MLE. Blocks: fairlead, mid-line and anchor failures with healthy sensors (24 runs
# each); the intact mooring with healthy sensors (12 h); each of 17 faults (GNSS: step,
# frozen, noisy, drift, dead, gain; gyro: step, frozen, noisy, drift, dead; a cell: step,
# stuck, noisy, drift, dead, gain) from 400 to 700 s on an intact mooring (6 runs of
# 1800 s each) and with a failure drawn in 200-1000 s, before, during or after it (6 runs
# of 1200 s each): fairlead breaks (a cell's fault on the parting line's cell, and again on
# a cell drawn from the eight), mid-line breaks and anchor releases.
"""

TRAINING = COMMON + """# The training campaign: the checks' and the fused detector's settings were chosen on it;
# scenarios/campaigns/sensor_faults.yaml is its held-out twin. Results: benchmarks/README.md,
# "Sensor faults: checks on the sensors and the fused detector".
#
#   moorsim batch scenarios/campaigns/training/sensor_faults_training.yaml --out out/sensor_faults_training
#   python3 tools/report.py out/sensor_faults_training
"""
HELD_OUT = COMMON + """# The held-out campaign: its own seed, nothing chosen on it; the results in the README and
# benchmarks/README.md are its. sensor_faults_training.yaml is its training twin.
#
#   moorsim batch scenarios/campaigns/sensor_faults.yaml --out out/sensor_faults
"""

INTACT = """# The false-alarm campaign: hours on an intact mooring, the set-up and detectors of
# sensor_faults.yaml (the turret-forward mooring, Hs 2.5, 4 and 6 m, any wave heading, the
# current none or 0.5 m/s, a load cell on every fairlead). 900 healthy hours (300 per sea
# state) and each of its 17 sensor faults from 300 s to the end of an hour (a drift for
# 600 s), 6 hours per fault. No line parts: every line named is a false alarm. Held out:
# nothing was chosen on it.
#
#   moorsim batch scenarios/campaigns/sensor_faults_intact.yaml --out out/sensor_faults_intact
"""

def focus_campaign(name):
    """A training-side campaign on one question, written outside the library (its scenario
    path absolute): "noisy_onset" (seed 3641: a noisier GNSS, alone 120 runs and with a
    fairlead break 48, and 48 healthy breaks; fused and deficit), "cell_faults_hs6" (seed
    3631: at Hs 6 m, five cell faults 40 runs each, three with a fairlead break or anchor
    release 16 each, and 32 of each failure with healthy sensors; fused) or "gnss_outage"
    (seed 3651: the GNSS dead or frozen from 300 s to the end of an hour, 36 runs each; a
    fairlead break during a 400-700 s outage, 24 runs each; 48 healthy breaks; fused and
    deficit)."""
    global SEA
    seed, detectors = {"noisy_onset": (3641, ("fused", "deficit")),
                       "cell_faults_hs6": (3631, ("fused",)),
                       "gnss_outage": (3651, ("fused", "deficit"))}[name]
    sea = SEA
    if name == "cell_faults_hs6":
        SEA = SEA.replace("values: [2.5, 4, 6]", "values: [6]")
    body = preamble(name, seed, f"# {name}: a training-side focus campaign")
    body = [l.replace("../library/", str(ROOT / "scenarios/library") + "/") for l in body]
    body = [l for l in body if not l.startswith("    - {type:") or
            any(f"type: {d}}}" in l for d in detectors)]
    by_name = {f[0]: f for f in FAULTS}
    if name == "noisy_onset":
        body.append(fault_block(*by_name["gnss_noisy"]).replace("seeds: 2", "seeds: 20"))
        body.append(fault_block(*by_name["gnss_noisy"], failure="fairlead")
                    .replace("seeds: 2", "seeds: 8"))
        body.append(failure_block("fairlead"))
    elif name == "gnss_outage":
        for block, mode in (("dead", "dead"), ("frozen", "stuck")):
            body.append("\n".join([
                f"  - name: gnss_{block}_hour", "    set:", "      simulation.duration: 3600",
                f"      sensors.gnss.faults: [{{mode: {mode}, time: 300}}]", "    factors:", SEA,
                HEADING, "    seeds: 12"]))
        for f in ("gnss_dead", "gnss_frozen"):
            body.append(fault_block(*by_name[f], failure="fairlead")
                        .replace("seeds: 2", "seeds: 8"))
        body.append(failure_block("fairlead").replace("seeds: 8", "seeds: 16"))
    else:
        for f in ("cell_step", "cell_stuck", "cell_drift", "cell_dead", "cell_gain"):
            body.append(fault_block(*by_name[f]).replace("seeds: 2", "seeds: 20"))
        for f in ("cell_step", "cell_dead", "cell_gain"):
            for failure in ("fairlead", "anchor"):
                body.append(fault_block(*by_name[f], failure=failure)
                            .replace("seeds: 2", "seeds: 8"))
        for failure in ("fairlead", "anchor", "midline"):
            body.append(failure_block(failure).replace("seeds: 8", "seeds: 16"))
    SEA = sea
    return "\n".join(body) + "\n"


if __name__ == "__main__":
    import sys
    if len(sys.argv) == 4 and sys.argv[1] == "--focus":
        Path(sys.argv[3]).write_text(focus_campaign(sys.argv[2]))
        sys.exit(0)
    schema = "# yaml-language-server: $schema=../moorsim-campaign.schema.json\n"
    out = ROOT / "scenarios/campaigns"
    # The training campaign sits one folder down, in training/: its paths reach one further.
    (out / "training" / "sensor_faults_training.yaml").write_text(
        schema.replace("../", "../../")
        + campaign("sensor_faults_training", 3601, TRAINING).replace(
            "scenario: ../library/", "scenario: ../../library/"))
    (out / "sensor_faults.yaml").write_text(schema + campaign("sensor_faults", 3602, HELD_OUT))
    (out / "sensor_faults_intact.yaml").write_text(
        schema + intact_campaign("sensor_faults_intact", 3603, INTACT, 150))
