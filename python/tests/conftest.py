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
