"""tools/plot_mooring.py draws a scenario's lines at rest, and refuses bad input in one line."""
import os
import subprocess
import sys

SOURCE = os.environ["MOORSIM_SOURCE_DIR"]
TOOL = os.path.join(SOURCE, "tools", "plot_mooring.py")
SEABED = os.path.join(SOURCE, "scenarios", "library", "seed_surveyed_seabed.yaml")


def plot(*args):
    return subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True,
                          timeout=300)


def test_draws_the_lines_at_rest(tmp_path):
    out = tmp_path / "layout.png"
    result = plot(SEABED, "--out", str(out), "--set", "mooring.lines[3].length=2300")
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == f"wrote {out}"
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_bad_scenario_or_output_is_one_line_and_exit_2(tmp_path):
    result = plot(str(tmp_path / "missing.yaml"))
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "missing.yaml" in result.stderr, result.stderr
    result = plot(SEABED, "--set", "mooring.water.depth=-3")
    assert result.returncode == 2
    assert "mooring.water.depth" in result.stderr and result.stderr.count("\n") == 1
    result = plot(SEABED, "--out", str(tmp_path / "no" / "such" / "folder.png"))
    assert result.returncode == 2
    assert "cannot write" in result.stderr and result.stderr.count("\n") == 1, result.stderr
