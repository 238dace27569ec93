"""The Python module (import moorsim) against the program it wraps: a run through
moorsim.run() is `moorsim run`'s run.h5 bit for bit; the plant stepped from Python with the
scenario's controller gives that run; detection replayed on arrays gives the run's
verdicts; the lines save and restore bit for bit; a campaign's table arrives as a
DataFrame; bad arguments raise, naming what is wrong."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import moorsim

SOURCE = os.environ["MOORSIM_SOURCE_DIR"]
CLI = os.environ["MOORSIM_CLI"]
THESIS = os.path.join(SOURCE, "scenarios/library/thesis_line6_current.yaml")
SEED = os.path.join(SOURCE, "scenarios/library/seed_tapm.yaml")
SHORT = {"simulation.duration": 40, "failure.time": 20}


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory):
    """The thesis case, 40 s with line 6 parting at 20 s, through the program."""
    out = tmp_path_factory.mktemp("cli")
    subprocess.run([CLI, "run", THESIS, "--quiet", "--out", str(out)]
                   + [a for k, v in SHORT.items() for a in ("--set", f"{k}={v}")], check=True)
    return moorsim.read_run(out)


def test_a_run_is_the_programs_run_bit_for_bit(cli_run):
    run = moorsim.run(THESIS, set=SHORT)
    assert run.status == "ok"
    assert run.summary["status"] == "ok"
    assert set(run.keys()) == set(cli_run.keys())
    for path in cli_run.keys():
        np.testing.assert_array_equal(run[path], cli_run[path], err_msg=path)
    assert run.summary["detectors"] == cli_run.summary["detectors"]
    assert run.columns("mooring/fairlead_tension")[5] == "line 6"


def test_a_run_file_whose_table_has_another_width_is_refused(cli_run, tmp_path):
    """read_run checks a file against the tables the writer declares."""
    import h5py

    out = tmp_path / "run.h5"
    with h5py.File(out, "w") as f:
        for path in cli_run.keys():
            f[path] = cli_run[path]
        del f["vessel/pose_measured"]
        f["vessel/pose_measured"] = cli_run["vessel/pose_measured"][:, :2]
    with pytest.raises(moorsim.InputError, match=r"/vessel/pose_measured: shape \(41, 2\), "
                                                 r"expected \(rows, 3\)"):
        moorsim.read_run(out)


def test_the_plant_stepped_from_python_with_the_scenarios_controller_gives_the_run(cli_run):
    plant = moorsim.Plant(THESIS, seed=1, overrides=[f"{k}={v}" for k, v in SHORT.items()])
    rows = []
    for t in cli_run.time:
        plant.advance_to(t)
        rows.append(plant.record())
    pose = np.array([r["pose"] for r in rows])
    tension = np.array([r["fairlead_tension"] for r in rows])
    np.testing.assert_array_equal(pose, cli_run["vessel/pose_true"])
    np.testing.assert_array_equal(tension, cli_run["mooring/fairlead_tension"])
    assert plant.hypotheses[6] == "line 6"


def test_the_users_own_thrust_command_moves_the_vessel():
    def surge_after(thrust):
        plant = moorsim.Plant(SEED, seed=3, overrides=["simulation.duration=300"])
        plant.set_thrust(thrust)
        plant.advance_to(300.0)
        return plant.record()
    pushed = surge_after([2.0e6, 0.0, 0.0])  # body frame: 2 MN forward
    held = surge_after([0.0, 0.0, 0.0])
    heading = pushed["pose"][5]
    forward = np.array([np.cos(heading), np.sin(heading)])
    moved = (pushed["pose"][:2] - held["pose"][:2]) @ forward
    assert moved > 1.0, moved
    np.testing.assert_allclose(pushed["thrust_commanded"], [2.0e6, 0.0, 0.0])


def test_detection_replayed_on_arrays_gives_the_runs_verdicts(cli_run):
    time = cli_run["detection/input/time"]
    pose = cli_run["detection/input/pose_measured"]
    thrust = cli_run["detection/input/thrust"]
    result = moorsim.detect(THESIS, time, pose, thrust, set=SHORT)
    assert result["hypotheses"][6] == "line 6"
    # The run records a row per output second; the detection input has every sample.
    rows = np.searchsorted(time, cli_run.time)
    for label, verdicts in result["detectors"].items():
        np.testing.assert_array_equal(verdicts["alarm"][rows],
                                      cli_run[f"detectors/{label}/alarm"].astype(bool))
        np.testing.assert_array_equal(verdicts["score"][rows],
                                      cli_run[f"detectors/{label}/score"], err_msg=label)


def test_lines_restore_repeats_bit_for_bit_and_parted_lines_go_with_the_state():
    lines = moorsim.Lines(SEED)
    assert lines.num_lines == 8 and lines.coupled_dofs == 6
    x, xd = np.zeros(6), np.zeros(6)
    f0 = lines.init(x, xd)
    assert f0.shape == (6,)

    def steps(n):
        out = []
        for _ in range(n):
            t = lines.time + 0.1
            x = np.array([3.0 * np.sin(0.1 * t), 0, 0.5 * np.sin(0.6 * t), 0, 0, 0])
            xd = np.array([0.3 * np.cos(0.1 * t), 0, 0.3 * np.cos(0.6 * t), 0, 0, 0])
            out.append(lines.step(x, xd, 0.1))
        return np.array(out)

    steps(20)
    state = lines.save()
    assert isinstance(state, bytes)
    first = steps(30)
    lines.restore(state)
    np.testing.assert_array_equal(steps(30), first)
    other = moorsim.Lines(SEED)
    other.restore(state)
    lines.restore(state)
    lines.part(6)
    parted = lines.save()
    other.restore(parted)
    np.testing.assert_array_equal(other.fairlead_tensions(), lines.fairlead_tensions())
    assert other.fairlead_tensions()[5] == 0.0
    assert lines.node_positions(1).shape == (lines.node_count(1), 3)
    assert lines.segment_tensions(1).shape == (lines.node_count(1) - 1,)


def test_bad_arguments_raise_naming_what_is_wrong():
    with pytest.raises(moorsim.InputError, match="nonexistent.yaml"):
        moorsim.Lines("/nonexistent.yaml")
    lines = moorsim.Lines(SEED)
    with pytest.raises(RuntimeError, match="not initialised"):
        lines.step(np.zeros(6), np.zeros(6), 0.1)
    lines.init(np.zeros(6), np.zeros(6))
    with pytest.raises(ValueError, match="x must hold 6 numbers, not 5"):
        lines.step(np.zeros(5), np.zeros(6), 0.1)
    with pytest.raises(moorsim.InputError, match="must be a number from 1e-09 to 86400 s"):
        lines.step(np.zeros(6), np.zeros(6), -1.0)
    with pytest.raises(moorsim.InputError, match="finite"):
        lines.step(np.full(6, np.nan), np.zeros(6), 0.1)
    with pytest.raises(IndexError, match="line 9 is not one of the lines 1..8"):
        lines.node_positions(9)
    with pytest.raises(ValueError, match="where must be"):
        lines.part(1, where="middle")
    with pytest.raises(moorsim.InputError, match="not a moorsim lines state"):
        lines.restore(b"x" * 64)
    with pytest.raises(moorsim.InputError, match="simulation.duration"):
        moorsim.run(THESIS, set={"simulation.duration": -1})


def test_a_campaign_arrives_as_a_table(tmp_path):
    campaign = tmp_path / "campaign.yaml"
    campaign.write_text(f"""scenario: {THESIS}
seed: 5
set:
  simulation.duration: 40
  failure.time: 20
blocks:
  - name: line6
    seeds: 2
""")
    table = moorsim.run_campaign(campaign, out=tmp_path / "out", threads=2)
    assert len(table) == 2
    assert (table["status"] == "ok").all()
    assert "dht.alarm_time" in table.columns
    again = moorsim.read_campaign(tmp_path / "out")
    assert again.equals(table)
    with pytest.raises(FileNotFoundError, match="no design checks"):
        moorsim.read_design(tmp_path / "out")


def test_a_design_campaign_arrives_as_its_tables(tmp_path):
    # The thesis chain with a breaking load and DNV's studless curve; three storms.
    (tmp_path / "plant.yaml").write_text(f"""base: {THESIS}
mooring:
  line_types:
    - {{name: chain_seed, diameter: 0.08, mass_per_length: 275, axial_stiffness: 2.28785e8,
       axial_damping_ratio: 0.5, drag_normal: 0.3, drag_tangential: 1.0, added_mass_normal: 1.5,
       minimum_breaking_load: 1.5e7, fatigue: {{curve: studless_chain}}}}
detectors: []
failure: ~
""")
    campaign = tmp_path / "design.yaml"
    campaign.write_text("""scenario: plant.yaml
seed: 5
set: {simulation.duration: 30, simulation.output_rate_hz: 5}
design: {standard: api_rp_2sk}
blocks:
  - name: storm
    design: {condition: intact}
    seeds: 3
  - name: sea_state
    design: {probability: 1}
    seeds: 1
""")
    moorsim.run_campaign(campaign, out=tmp_path / "out", threads=2)
    design = moorsim.read_design(tmp_path / "out")
    extremes = design["extremes"]
    assert list(extremes["line"]) == list(range(1, 9))
    assert (extremes["result"] == "pass").all()
    assert (extremes["required_factor"] == 1.67).all()
    np.testing.assert_allclose(extremes["safety_factor"], 1.5e7 / extremes["design_tension"])
    assert len(design["offsets"]) == 1
    fatigue = design["fatigue"]
    assert len(fatigue) == 16 and (fatigue["life_years"] > 0).all()
    assert design["checks"]["fatigue"]["probability"] == 1
    # The report shows them, and report.json holds them as design.json does.
    report = subprocess.run([sys.executable, os.path.join(SOURCE, "tools/report.py"),
                             str(tmp_path / "out")], capture_output=True, text=True)
    assert report.returncode == 0, report.stderr
    assert "<h2>Design checks</h2>" in (tmp_path / "out" / "report.html").read_text()
    with open(tmp_path / "out" / "report.json") as f:
        assert json.load(f)["design"] == design["checks"]


def test_a_run_as_an_xarray_dataset(cli_run):
    xr = pytest.importorskip("xarray")
    ds = cli_run.to_xarray()
    tension = ds["mooring.fairlead_tension"]
    assert tension.dims == ("time", "mooring.fairlead_tension.column")
    assert tension.attrs["units"] == "N"
    np.testing.assert_array_equal(tension.sel({"mooring.fairlead_tension.column": "line 6"}),
                                  cli_run["mooring/fairlead_tension"][:, 5])
    assert isinstance(ds, xr.Dataset)


def test_the_plant_restored_repeats_bit_for_bit():
    overrides = ["simulation.duration=60", "mooring.defaults.segments=12"]
    plant = moorsim.Plant(SEED, seed=2, overrides=overrides)
    plant.advance_to(5.0)
    plant.set_thrust([5.0e5, 0.0, 0.0])
    plant.advance_to(8.0)
    state = plant.save()
    plant.advance_to(15.0)
    on = plant.record()
    again = moorsim.Plant(SEED, seed=2, overrides=overrides)
    again.restore(state)
    assert again.time == 8.0
    again.advance_to(15.0)
    np.testing.assert_array_equal(again.record()["pose"], on["pose"])
    np.testing.assert_array_equal(again.record()["thrust_delivered"], on["thrust_delivered"])
    with pytest.raises(moorsim.InputError, match="another model"):
        moorsim.Plant(SEED, seed=3, overrides=overrides).restore(state)
