"""Time-varying continuous models: ContinuousLtvModel on the periodic MIMO plant
of the Besancon and Zhang examples (Zhang 2005, Algorithms 3 and 4), against
the C++ examples' CSV, pickled with its functions, and refused where an
algorithm needs a constant model."""

import math
import pickle

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import assert_matches_recorded_samples, cxx_example_table

QUADRATIC = dict(input="quadratic", output="quadratic", excitation_window=629)


@pytest.fixture(scope="module")
def periodic():
    return adaptobs.examples.periodic(), adaptobs.examples.simulate_periodic(4001)


def model(system):
    return adaptobs.ContinuousLtvModel(system["matrices_at"], system["Phi"], np=2)


def besancon(system):
    transform = adaptobs.StaticTransform(system["T"], np.zeros((4, 2)))
    return adaptobs.BesanconObserver(model(system), transform, system["K1"], system["gamma"], np.zeros(4),
                                     np.zeros(2), **QUADRATIC)


def zhang(system, gamma=50.0):
    return adaptobs.ZhangContinuousObserver(model(system), system["K"], gamma * np.eye(2), np.zeros(4), np.zeros(2),
                                            **QUADRATIC)


def run(observer, data, n=None):
    n = len(data["t"]) if n is None else n
    return observer.run(data["t"][:n], data["U"][:n], data["Y"][:n], data["U_mid"][:n], data["Y_mid"][:n])


def matrices_in_numpy(t):
    """The plant's A(t), B, C written from its definition (examples/models/periodic_mimo.hpp)."""
    w = 1 + 0.5 * math.sin(t)
    Ao = np.array([[-1, 0.5 + 0.5 * math.sin(t), 1, 0], [-0.5, -1.5, 0.5 * math.cos(t), 1],
                   [0.3, 0, -2, w], [0, -0.3, -w, -2]])
    T = np.array([[1.0, 0, 1, 0], [0, 1, 0, -1], [0, 0, 1, 0], [0, 0, 0, 1]])
    C = np.array([[1.0, 0, 1, 0], [0, 1, 0, -1]])
    return np.linalg.solve(T, Ao @ T), np.array([[0.0], [1], [0], [1]]), C


def phi_in_numpy(t):
    return np.array([[math.sin(t), 0], [0, math.cos(0.7 * t)], [1, 0], [0, math.sin(1.3 * t)]])


def test_the_model_gives_the_plant_s_matrices(periodic):
    system, _ = periodic
    m = model(system)
    assert m.sizes == (4, 1, 2, 2)
    for t in (0.0, 1.3, 5.0):
        for ours, reference in zip(m.at(t), matrices_in_numpy(t)):
            assert np.allclose(ours, reference, rtol=0, atol=1e-14)


@pytest.mark.parametrize("make, name", [(besancon, "besancon"), (zhang, "zhang_continuous")])
def test_the_replay_matches_the_cxx_example(tmp_path, periodic, make, name):
    table = cxx_example_table(tmp_path, name)
    system, data = periodic
    assert_matches_recorded_samples(table, data, run(make(system), data), every=5, states=4)


@pytest.mark.parametrize("make", [besancon, zhang])
def test_theta_converges_on_the_periodic_plant(periodic, make):
    system, data = periodic
    result = run(make(system), data)
    assert np.all(result.status == UpdateStatus.accepted)
    assert np.linalg.norm(result.parameters[-1] - system["theta"]) < 1e-2
    # The same observer over NumPy functions of the plant: the same estimates to rounding.
    numpy_model = adaptobs.ContinuousLtvModel(matrices_in_numpy, phi_in_numpy, np=2)
    observer = make(system)
    twin = type(observer)(numpy_model, *_design_of(observer, system), **QUADRATIC)
    assert np.max(np.abs(run(twin, data, 1000).parameters - result.parameters[:1000])) < 1e-9


def _design_of(observer, system):
    if isinstance(observer, adaptobs.BesanconObserver):
        return adaptobs.StaticTransform(system["T"], np.zeros((4, 2))), system["K1"], system["gamma"], np.zeros(4), \
            np.zeros(2)
    return system["K"], 50.0 * np.eye(2), np.zeros(4), np.zeros(2)


def test_pickled_with_its_functions_it_continues_bit_for_bit(periodic):
    system, data = periodic
    numpy_model = adaptobs.ContinuousLtvModel(matrices_in_numpy, phi_in_numpy, np=2)
    observer = adaptobs.ZhangContinuousObserver(numpy_model, system["K"], 50.0 * np.eye(2), np.zeros(4), np.zeros(2),
                                                **QUADRATIC)
    run(observer, data, 300)
    twin = pickle.loads(pickle.dumps(observer))
    rest = [data[k][300:600] for k in ("t", "U", "Y", "U_mid", "Y_mid")]
    assert np.array_equal(observer.run(*rest).parameters, twin.run(*rest).parameters)
    restored_model = pickle.loads(pickle.dumps(numpy_model))
    assert restored_model.matrices_at is matrices_in_numpy and restored_model.sizes == (4, 1, 2, 2)


def test_refusals_name_the_argument(periodic):
    system, data = periodic
    with pytest.raises(TypeError, match=r"'matrices_at' must be a callable t -> \(A, B, C\)"):
        adaptobs.ContinuousLtvModel(np.eye(4), system["Phi"], np=2)
    with pytest.raises(TypeError, match=r"'matrices_at\(0\)' must be a tuple \(A, B, C\)"):
        adaptobs.ContinuousLtvModel(lambda t: np.eye(4), system["Phi"], np=2)
    # Algorithms 1 and 2 rest on an SPR transfer function: a time-varying model is refused.
    siso = adaptobs.examples.siso()
    ltv = adaptobs.ContinuousLtvModel(lambda t: (siso["A"], siso["B"], siso["C"]), np.zeros((3, 2)))
    transform = adaptobs.bastin_gevers_form(siso["A"], siso["C"], [1.0, 4.0, 3.0])
    with pytest.raises(ConfigurationError, match=r"BastinGevers.*'model' must be time invariant"):
        adaptobs.BastinGeversObserver(ltv, transform, np.ones((3, 1)), np.eye(2), np.zeros(3), np.zeros(2))
    # Matrices of another size at a later time: ConfigurationError from run(), the estimates kept.
    shrinking = adaptobs.ContinuousLtvModel(
        lambda t: matrices_in_numpy(t) if t < 0.5 else (np.eye(3), np.zeros((3, 1)), np.zeros((2, 3))),
        phi_in_numpy, np=2)
    observer = adaptobs.ZhangContinuousObserver(shrinking, system["K"], 50.0 * np.eye(2), np.zeros(4), np.zeros(2))
    run(observer, data, 40)
    theta = observer.parameters
    with pytest.raises(ConfigurationError, match=r"'matrices_at\(t\)\[0\]' must be 4x4 \(got 3x3\)"):
        run(observer, data, 60)
    assert np.array_equal(observer.parameters, theta)


def test_a_function_that_raises_in_update_leaves_the_observer_as_it_was(periodic):
    """C(t_k) is read after the integration: a matrices_at that fails there changes nothing."""
    system, data = periodic

    def failing_after(limit):
        def matrices_at(t):
            if t > limit:
                raise RuntimeError("outside the function's domain")
            return matrices_in_numpy(t)
        return matrices_at

    observer = adaptobs.ZhangContinuousObserver(adaptobs.ContinuousLtvModel(failing_after(0.1), phi_in_numpy, np=2),
                                                system["K"], 50.0 * np.eye(2), np.zeros(4), np.zeros(2))
    for k in range(10):
        assert observer.update(data["t"][k], data["U"][k], data["Y"][k]) == UpdateStatus.accepted
    before = (observer.internal_state, observer.time, observer.output_error)
    with pytest.raises(RuntimeError, match="outside the function's domain"):
        observer.update(data["t"][11], data["U"][11], data["Y"][11])
    assert np.array_equal(observer.internal_state, before[0]) and observer.time == before[1]
    assert np.array_equal(observer.output_error, before[2])
    # A run that fails at its sixth sample leaves no trace of the first five.
    fresh = adaptobs.ZhangContinuousObserver(adaptobs.ContinuousLtvModel(failing_after(0.05), phi_in_numpy, np=2),
                                             system["K"], 50.0 * np.eye(2), np.zeros(4), np.zeros(2))
    with pytest.raises(RuntimeError):
        fresh.run(data["t"][:10], data["U"][:10], data["Y"][:10])
    assert fresh.time == 0.0 and not fresh.internal_state.any()
