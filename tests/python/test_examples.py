"""The Python examples (examples/python/) run to their end and find what they look for."""
import os
import subprocess
import sys

import pytest

EXAMPLES = os.path.join(os.environ["MOORSIM_SOURCE_DIR"], "examples", "python")


def run_example(name, *args):
    result = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def test_the_branching_bank_names_the_parted_line():
    out = run_example("particle_filter.py")
    assert "named line 3 at" in out, out


def test_the_python_detector_names_line_6_beside_moorsims():
    out = run_example("python_detector.py")
    assert "python drift detector: line 6 at" in out, out
    assert "moorsim DHT: line 6 at" in out, out


def test_a_campaigns_table_is_analyzed():
    out = run_example("campaign_analysis.py")
    assert "4 runs with a failure" in out, out
    for detector in ("dht", "mle", "glr", "deficit"):
        assert f"\n{detector} " in out, out
