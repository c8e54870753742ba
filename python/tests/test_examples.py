"""The Python example programs run, print their figures of merit, and refuse
nonsense arguments (without matplotlib: --no-figure)."""

import pathlib
import subprocess
import sys

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def run(name, *arguments):
    return subprocess.run([sys.executable, str(EXAMPLES / name), *arguments], capture_output=True, text=True)


def test_the_satellite_example_estimates_the_thrust_efficiencies():
    done = run("satellite.py", "--no-figure")
    assert done.returncode == 0, done.stderr
    assert "theta_hat = [1.00786385 1.49253134]" in done.stdout
    refused = run("satellite.py", "--seconds", "-5")
    assert refused.returncode == 2 and "--seconds must lie in [1, 1e6]" in refused.stderr


def test_the_fault_example_detects_and_isolates_the_thruster_fault():
    done = run("satellite_fault.py", "--no-figure")
    assert done.returncode == 0, done.stderr
    assert "cusum: 10.0 s after the fault" in done.stdout
    assert "isolated: theta_2, direction -1" in done.stdout
    refused = run("satellite_fault.py", "--fault-size", "-1.5")
    assert refused.returncode == 2 and "--fault-size must lie in (-1, 10)" in refused.stderr
