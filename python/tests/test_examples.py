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


def test_the_guiro_example_places_the_gains_and_estimates_theta():
    done = run("guiro.py", "--no-figure")
    assert done.returncode == 0, done.stderr
    assert "Gamma = 1.87307728" in done.stdout  # the printed 1.8730773, decimal point corrected
    theta = float(done.stdout.split("theta_hat =")[1].split()[0])
    assert abs(theta - 5.0) < 1e-6
    lossy = run("guiro.py", "--no-figure", "--loss", "0.3", "--samples", "200")
    assert lossy.returncode == 0 and "lost samples: 57" in lossy.stdout, lossy.stderr
    assert abs(float(lossy.stdout.split("theta_hat =")[1].split()[0]) - 5.0) < 1e-6
    refused = run("guiro.py", "--loss", "1")
    assert refused.returncode == 2 and "--loss must lie in [0, 1)" in refused.stderr


def test_the_waste_water_example_estimates_theta_with_and_without_lost_outputs():
    done = run("wwtp.py", "--no-figure")
    assert done.returncode == 0, done.stderr
    assert abs(float(done.stdout.split("theta_hat =")[1].split()[0]) - 0.1) < 1e-4
    lossy = run("wwtp.py", "--no-figure", "--loss", "0.2")
    assert lossy.returncode == 0 and "lost outputs: 100" in lossy.stdout, lossy.stderr
    assert abs(float(lossy.stdout.split("theta_hat =")[1].split()[0]) - 0.1) < 1e-4
    refused = run("wwtp.py", "--steps", "1")
    assert refused.returncode == 2 and "--steps must lie in [2, 1e6]" in refused.stderr


def test_the_unified_example_runs_the_five_estimators():
    done = run("unified.py", "--no-figure", "--seconds", "100")
    assert done.returncode == 0, done.stderr
    errors = [float(line.rsplit("error", 1)[1]) for line in done.stdout.splitlines()]
    assert len(errors) == 5 and max(errors[:4]) < 1e-6 and errors[4] < 1e-2  # the filter's random walk in theta
    refused = run("unified.py", "--noise", "-1")
    assert refused.returncode == 2 and "--noise must lie in [0, 1]" in refused.stderr


def test_the_dey_bhasin_example_identifies_the_system_only_with_a_rich_input():
    done = run("dey_bhasin_mimo.py", "--no-figure")
    assert done.returncode == 0, done.stderr
    lines = dict(line.split(": ", 1) for line in done.stdout.splitlines())
    worst = {name: float(text.split("= ")[1].split(",")[0]) for name, text in lines.items()}
    assert worst["rich input"] < 1e-10 and worst["not rich input"] > 1.0
    refused = run("dey_bhasin_mimo.py", "--steps", "5")
    assert refused.returncode == 2 and "--steps must lie in [10, 1e6]" in refused.stderr
