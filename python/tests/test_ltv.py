"""Time-varying discrete models: DiscreteLtvModel from per-step arrays or a
function of k, under the Guyader-Zhang observer, the augmented Kalman filter
and Guiro's observer."""

import copy
import pickle

import numpy as np
import pytest

import adaptobs
from adaptobs import UpdateStatus
from conftest import make_filter, make_observer, step_by_step

N = 400


def varying_plant(steps=N):
    """x_{k+1} = A_k x_k + B u_k + Psi_k theta, y_k = C_k x_k with A_k and C_k
    changing every step (both Schur stable and observable at every k), a
    persistently exciting Psi_k and theta = (0.7, -0.3); noise free."""
    k = np.arange(steps)
    A = np.zeros((steps, 2, 2))
    A[:, 0, 0] = 0.5 + 0.2 * np.sin(k / 7)
    A[:, 0, 1] = 0.3 * np.cos(k / 5)
    A[:, 1, 1] = 0.4
    C = np.zeros((steps, 1, 2))
    C[:, 0, 0] = 1.0
    C[:, 0, 1] = 0.5 + 0.4 * np.sin(k / 11)
    B = np.array([[0.0], [1.0]])
    rng = np.random.default_rng(11)
    U = rng.standard_normal((steps, 1))
    Psi = rng.standard_normal((steps, 2, 2))
    theta = np.array([0.7, -0.3])
    x = np.array([1.0, -1.0])
    Y = np.zeros((steps, 1))
    for j in range(steps):
        Y[j] = C[j] @ x
        x = A[j] @ x + B @ U[j] + Psi[j] @ theta
    return dict(A=A, B=B, C=C, U=U, Psi=Psi, Y=Y, theta=theta)


def guyader_zhang_in_numpy(plant, K, mu, x0, theta0):
    """Eq. (2a)-(2c) of Guyader & Zhang (2003) with the matrices of step k."""
    x, theta = x0.copy(), theta0.copy()
    upsilon = np.zeros((2, 2))
    thetas = []
    for k in range(len(plant["Y"])):
        A, C = plant["A"][k], plant["C"][k]
        e = plant["Y"][k] - C @ x
        theta_next = theta + mu * upsilon.T @ C.T @ e  # (2b)
        upsilon_next = (A - K @ C) @ upsilon + plant["Psi"][k]  # (2a)
        x = (A @ x + plant["B"] @ plant["U"][k] + plant["Psi"][k] @ theta + K @ e
             + upsilon_next @ (theta_next - theta))  # (2c)
        theta, upsilon = theta_next, upsilon_next
        thetas.append(theta)
    return np.array(thetas)


@pytest.fixture(scope="module")
def plant():
    return varying_plant()


def ltv_observer(plant, model=None):
    model = model or adaptobs.DiscreteLtvModel(plant["A"], plant["B"], plant["C"], np=2)
    return adaptobs.GuyaderZhangObserver(model, K=np.zeros((2, 1)), mu=0.2, x0=np.zeros(2), theta0=np.zeros(2))


def test_the_observer_follows_the_matrices_of_each_step(plant):
    """Equal to eq. (2) written in NumPy, and theta converges; the model frozen
    at its mean matrices leaves a bias."""
    result = ltv_observer(plant).run(plant["U"], plant["Y"], plant["Psi"])
    reference = guyader_zhang_in_numpy(plant, np.zeros((2, 1)), 0.2, np.zeros(2), np.zeros(2))
    assert np.max(np.abs(result.parameters - reference)) < 1e-12
    assert np.max(np.abs(result.parameters[-1] - plant["theta"])) < 1e-6
    frozen = adaptobs.DiscreteLtiModel(plant["A"].mean(axis=0), plant["B"], plant["C"].mean(axis=0), np=2)
    biased = ltv_observer(plant, frozen).run(plant["U"], plant["Y"], plant["Psi"])
    assert np.max(np.abs(biased.parameters[-1] - plant["theta"])) > 1e-2


def test_a_function_of_k_gives_the_model_of_its_arrays(plant):
    by_function = adaptobs.DiscreteLtvModel.from_function(
        lambda k: (plant["A"][k], plant["B"], plant["C"][k]), steps=N, np=2)
    assert by_function.steps == N and by_function.sizes == (2, 1, 1, 2)
    assert np.array_equal(by_function.A, plant["A"])
    assert np.array_equal(by_function.B, np.broadcast_to(plant["B"], (N, 2, 1)))
    a = ltv_observer(plant).run(plant["U"], plant["Y"], plant["Psi"])
    b = ltv_observer(plant, by_function).run(plant["U"], plant["Y"], plant["Psi"])
    assert np.array_equal(a.parameters, b.parameters)


@pytest.mark.parametrize("make", [make_observer, make_filter])
def test_constant_steps_give_the_time_invariant_estimates(satellite, make):
    """The satellite's matrices repeated for every step: the LTV model reproduces the LTI one."""
    system, data = satellite
    lti = make(system)
    ltv = make(system)
    steps = 300
    model = adaptobs.DiscreteLtvModel(np.broadcast_to(system["A"], (steps, 4, 4)), system["B"], system["C"], np=2)
    rebuilt = type(ltv)(model, *_arguments_after_model(ltv, system))
    a = lti.run(data["U"][:steps], data["Y"][:steps], data["Psi"][:steps])
    b = rebuilt.run(data["U"][:steps], data["Y"][:steps], data["Psi"][:steps])
    assert np.max(np.abs(a.parameters - b.parameters)) < 1e-12
    assert np.max(np.abs(a.state - b.state)) < 1e-12


def _arguments_after_model(observer, system):
    if isinstance(observer, adaptobs.GuyaderZhangObserver):
        return system["K"], system["mu"], system["x0_estimate"], system["theta0_estimate"]
    p0 = np.diag([0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0])
    q = np.diag([1e-10] * 4 + [0.0, 0.0])
    return system["x0_estimate"], system["theta0_estimate"], p0, q, np.eye(2) * 1e-4


def test_run_equals_a_loop_of_update_with_masks(plant):
    present = np.random.default_rng(3).random((N, 1)) > 0.2
    Y = plant["Y"].copy()
    Y[50] = np.nan
    a, b = ltv_observer(plant), ltv_observer(plant)
    result = a.run(plant["U"], Y, plant["Psi"], present=present)
    x, theta, error, status = step_by_step(b, plant["U"], Y, plant["Psi"], present)
    assert np.array_equal(result.parameters, theta) and np.array_equal(result.state, x)
    assert np.array_equal(result.status, status)
    assert result.status[50] == (UpdateStatus.nonfinite_input if present[50, 0] else UpdateStatus.accepted)


def test_beyond_the_last_step_nothing_changes(plant):
    observer = ltv_observer(plant)
    with pytest.raises(adaptobs.ConfigurationError, match=r"'Y'.*401 samples from step 0.*400 steps"):
        observer.run(plant["U"][[0] * (N + 1)], plant["Y"][[0] * (N + 1)], plant["Psi"][[0] * (N + 1)])
    assert observer.step == 0 and not observer.parameters.any()
    observer.run(plant["U"], plant["Y"], plant["Psi"])
    state, theta = observer.state, observer.parameters
    with pytest.raises(adaptobs.ConfigurationError, match=r"steps 0 to 399; step 400 is beyond"):
        observer.update(plant["U"][0], plant["Y"][0], plant["Psi"][0])
    assert np.array_equal(observer.state, state) and np.array_equal(observer.parameters, theta)
    assert observer.step == N


def test_pickle_and_deepcopy_continue_bit_for_bit(plant):
    half = N // 2
    observer = ltv_observer(plant)
    observer.run(plant["U"][:half], plant["Y"][:half], plant["Psi"][:half])
    rest = (plant["U"][half:], plant["Y"][half:], plant["Psi"][half:])
    restored = pickle.loads(pickle.dumps(observer))
    copied = copy.deepcopy(observer)
    expected = observer.run(*rest).parameters
    assert np.array_equal(restored.run(*rest).parameters, expected)
    assert np.array_equal(copied.run(*rest).parameters, expected)
    model = pickle.loads(pickle.dumps(adaptobs.DiscreteLtvModel(plant["A"], plant["B"], plant["C"], np=2)))
    assert np.array_equal(model.C, plant["C"]) and model.steps == N


def test_a_snapshot_over_other_steps_is_refused(plant):
    short = adaptobs.DiscreteLtvModel(plant["A"][:10], plant["B"], plant["C"][:10], np=2)
    with pytest.raises(adaptobs.ConfigurationError, match=r"model.steps' = 400 where this.* has 10"):
        ltv_observer(plant, short).restore(ltv_observer(plant).snapshot())


def test_bad_models_name_the_argument(plant):
    A, B, C = plant["A"], plant["B"], plant["C"]
    with pytest.raises(adaptobs.ConfigurationError, match=r"'C' must be 400 steps.*\(got \(10, 1, 2\)\)"):
        adaptobs.DiscreteLtvModel(A, B, C[:10], np=2)
    with pytest.raises(adaptobs.ConfigurationError, match=r"'A' \(or B or C\) must be given per step"):
        adaptobs.DiscreteLtvModel(A[0], B, C[0], np=2)
    with pytest.raises(adaptobs.ConfigurationError, match=r"'A' must be steps x rows x cols"):
        adaptobs.DiscreteLtvModel(A[None], B, C, np=2)
    bad = A.copy()
    bad[7, 1, 0] = np.nan
    with pytest.raises(adaptobs.ConfigurationError, match=r"'A\[7\]' must contain only finite numbers"):
        adaptobs.DiscreteLtvModel(bad, B, C, np=2)
    with pytest.raises(adaptobs.ConfigurationError, match=r"'C\[0\]' must be 1x2 \(got 1x3\)"):
        adaptobs.DiscreteLtvModel(A, B, np.zeros((N, 1, 3)), np=2)
    bad_step = lambda k: (A[k], B, C[k] if k != 4 else np.full((1, 2), np.inf))  # noqa: E731
    with pytest.raises(adaptobs.ConfigurationError, match=r"'matrices_at\(4\)\[2\]' must contain only finite"):
        adaptobs.DiscreteLtvModel.from_function(bad_step, steps=6, np=2)
    with pytest.raises(adaptobs.ConfigurationError, match=r"DiscreteLtvModel.at: argument 'k' must lie in \[0, 400\)"):
        adaptobs.DiscreteLtvModel(A, B, C, np=2).at(400)
    with pytest.raises(TypeError, match=r"'matrices_at\(2\)' must be a tuple \(A, B, C\)"):
        adaptobs.DiscreteLtvModel.from_function(lambda k: (A[k], B, C[k]) if k < 2 else None, steps=3, np=2)
    with pytest.raises(TypeError, match=r"'model' must be an adaptobs.DiscreteLtiModel or DiscreteLtvModel"):
        adaptobs.GuyaderZhangObserver("model", np.zeros((2, 1)), 0.1, np.zeros(2), np.zeros(2))
