import copy
import importlib.util
import os
import pathlib
import pickle
import subprocess

import numpy as np
import pytest

import adaptobs


@pytest.fixture(scope="session")
def satellite():
    """The satellite of Guyader & Zhang (2003), section 4, and 3000 noisy samples (seed 2003)."""
    system = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(3000, noise=0.01, seed=2003)
    return system, data


def make_observer(system, **options):
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)
    return adaptobs.GuyaderZhangObserver(
        model, system["K"], system["mu"], system["x0_estimate"], system["theta0_estimate"], **options
    )


def make_filter(system):
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)
    p0 = np.diag([0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0])
    q = np.diag([1e-10] * 4 + [0.0, 0.0])
    return adaptobs.AugmentedKalmanFilter(
        model, system["x0_estimate"], system["theta0_estimate"], P0=p0, Q=q, R=np.eye(2) * 1e-4
    )


def step_by_step(observer, U, Y, Psi, present=None):
    """A Python loop of update(): the estimates after each sample and the statuses."""
    x, theta, error, status = [], [], [], []
    for k in range(len(Y)):
        mask = None if present is None else present[k]
        status.append(observer.update(U[k], Y[k], Psi[k], present=mask))
        x.append(observer.state)
        theta.append(observer.parameters)
        error.append(observer.output_error)
    return np.array(x), np.array(theta), np.array(error), np.array(status)


def cxx_example_table(tmp_path, example, *arguments, csv=None, unbuilt=None):
    """The CSV (columns by name, default file `example`.csv) that the built C++ example `example` writes
    into tmp_path when run with `arguments`. The calling test is skipped when ADAPTOBS_EXAMPLES_DIR (the
    built C++ examples) is not set, and with the reason `unbuilt` when that example was not built."""
    examples = os.environ.get("ADAPTOBS_EXAMPLES_DIR")
    if not examples:
        pytest.skip("ADAPTOBS_EXAMPLES_DIR (the built C++ examples) is not set")
    program = os.path.join(examples, example)
    if unbuilt is not None and not os.path.exists(program):
        pytest.skip(unbuilt)
    subprocess.run([program, "--out", str(tmp_path), *arguments], check=True, capture_output=True)
    return np.genfromtxt(tmp_path / (csv or f"{example}.csv"), delimiter=",", names=True)


def assert_matches_recorded_samples(table, data, result, every, states):
    """A continuous-time example records every `every`-th sample: the same times, and the same two
    parameter estimates and `states` state estimates to 1e-12."""
    assert np.array_equal(data["t"][::every], table["t"])
    cxx = np.column_stack([table["thetahat_1"], table["thetahat_2"]])
    assert np.max(np.abs(result.parameters[::every] - cxx)) <= 1e-12
    cxx_state = np.column_stack([table[f"xhat_{i}"] for i in range(1, states + 1)])
    assert np.max(np.abs(result.state[::every] - cxx_state)) <= 1e-12


def assert_update_follows_run(make, U, Y, present, copies, fields=("state", "parameters")):
    """Runs make() over the samples, and steps a second make() through them by update(), replacing it by
    its copy at the steps that `copies` maps to "pickle", "deepcopy" or "copy": every update returns the
    status of the run and leaves `fields` bit for bit as the run has them. Returns the run's result, the
    observer that ran and the stepped one."""
    duplicate = {"pickle": lambda o: pickle.loads(pickle.dumps(o)), "deepcopy": copy.deepcopy, "copy": copy.copy}
    batch = make()
    result = batch.run(U, Y, present=present)
    stepped = make()
    for k in range(len(Y)):
        if k in copies:
            stepped = duplicate[copies[k]](stepped)
        assert stepped.update(U[k], Y[k], present=present[k]) == result.status[k], k
        for field in fields:
            assert np.array_equal(getattr(stepped, field), getattr(result, field)[k]), (field, k)
    return result, batch, stepped


def load_example(name):
    """A module of python/examples (its functions; main() is not run)."""
    path = pathlib.Path(__file__).resolve().parents[1] / "examples" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
