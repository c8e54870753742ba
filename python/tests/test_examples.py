"""The Python example programs run, print their figures of merit, and refuse
nonsense arguments (without matplotlib: --no-figure)."""

import pathlib
import subprocess
import sys

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def run(name, *arguments):
    return subprocess.run([sys.executable, str(EXAMPLES / name), *arguments], capture_output=True, text=True)


def output_of(name, *arguments):
    """What the example prints when run with `arguments`, which it must accept."""
    done = run(name, *arguments)
    assert done.returncode == 0, done.stderr
    return done.stdout


def assert_refuses(name, *arguments, message):
    """The example refuses `arguments` as argparse does (exit status 2), saying `message`."""
    refused = run(name, *arguments)
    assert refused.returncode == 2 and message in refused.stderr


def estimate_after(text, stdout):
    """The first number printed after `text`."""
    return float(stdout.split(text)[1].split()[0])


def test_the_satellite_example_estimates_the_thrust_efficiencies():
    assert "theta_hat = [1.00786385 1.49253134]" in output_of("satellite.py", "--no-figure")
    assert_refuses("satellite.py", "--seconds", "-5", message="--seconds must lie in [1, 1e6]")


def test_the_fault_example_detects_and_isolates_the_thruster_fault():
    stdout = output_of("satellite_fault.py", "--no-figure")
    assert "cusum: 10.0 s after the fault" in stdout
    assert "isolated: theta_2, direction -1" in stdout
    assert_refuses("satellite_fault.py", "--fault-size", "-1.5", message="--fault-size must lie in (-1, 10)")


def test_the_guiro_example_places_the_gains_and_estimates_theta():
    stdout = output_of("guiro.py", "--no-figure")
    assert "Gamma = 1.87307728" in stdout  # the printed 1.8730773, decimal point corrected
    assert abs(estimate_after("theta_hat =", stdout) - 5.0) < 1e-6
    lossy = output_of("guiro.py", "--no-figure", "--loss", "0.3", "--samples", "200")
    assert "lost samples: 57" in lossy
    assert abs(estimate_after("theta_hat =", lossy) - 5.0) < 1e-6
    assert_refuses("guiro.py", "--loss", "1", message="--loss must lie in [0, 1)")


def test_the_waste_water_example_estimates_theta_with_and_without_lost_outputs():
    assert abs(estimate_after("theta_hat =", output_of("wwtp.py", "--no-figure")) - 0.1) < 1e-4
    lossy = output_of("wwtp.py", "--no-figure", "--loss", "0.2")
    assert "lost outputs: 100" in lossy
    assert abs(estimate_after("theta_hat =", lossy) - 0.1) < 1e-4
    assert_refuses("wwtp.py", "--steps", "1", message="--steps must lie in [2, 1e6]")


def test_the_unified_example_runs_the_five_estimators():
    stdout = output_of("unified.py", "--no-figure", "--seconds", "100")
    errors = [float(line.rsplit("error", 1)[1]) for line in stdout.splitlines()]
    assert len(errors) == 5 and max(errors[:4]) < 1e-6 and errors[4] < 1e-2  # the filter's random walk in theta
    assert_refuses("unified.py", "--noise", "-1", message="--noise must lie in [0, 1]")


def test_the_dey_bhasin_example_identifies_the_system_only_with_a_rich_input():
    lines = dict(line.split(": ", 1) for line in output_of("dey_bhasin_mimo.py", "--no-figure").splitlines())
    worst = {name: float(text.split("= ")[1].split(",")[0]) for name, text in lines.items()}
    assert worst["rich input"] < 1e-10 and worst["not rich input"] > 1.0
    assert_refuses("dey_bhasin_mimo.py", "--steps", "5", message="--steps must lie in [10, 1e6]")
