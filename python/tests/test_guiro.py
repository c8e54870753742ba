"""The observer of Guiro, Iggidr, Ngom & Toure (2008) from Python: its gain
design against the error matrix written here in NumPy, convergence on the
paper's example with and without lost samples, and pickling."""

import pickle

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import cxx_example_table


@pytest.fixture(scope="module")
def guiro():
    return adaptobs.examples.guiro(), adaptobs.examples.simulate_guiro(200)


def make_observer(system, K, Gamma):
    model = adaptobs.DiscreteLtiModel(system["E"], system["B"], system["C"], np=1)
    return adaptobs.GuiroObserver(model, K, Gamma, system["z0"], system["theta0"], correct_initial_estimate=False)


def test_the_designed_gains_place_the_spectrum_of_the_error_matrix(guiro):
    system, _ = guiro
    E, C, H = system["E"], system["C"], system["H0"]
    gains = adaptobs.design_guiro_gains(E, C, H, system["poles"])
    ikc_e = (np.eye(2) - gains.K @ C) @ E
    U = np.block([[ikc_e, ikc_e @ H], [-gains.Gamma @ C, np.eye(1)]])
    assert np.allclose(U, gains.U, rtol=0, atol=1e-14)
    assert np.allclose(np.sort(np.linalg.eigvals(U).real), np.sort(system["poles"]), atol=1e-10)
    assert gains.spectral_radius == pytest.approx(0.6, abs=1e-10)
    # The printed gains (Gamma with its decimal point corrected) are the same design to their 7 digits.
    assert np.allclose(gains.K[:, 0], system["printed_K"], atol=1e-6)
    assert gains.Gamma[0, 0] == pytest.approx(system["printed_Gamma"], abs=1e-6)
    with pytest.raises(ConfigurationError, match="design_guiro_gains"):
        adaptobs.design_guiro_gains(E, C, H, [0.5, 1.5, 0.2])


def test_theta_converges_on_the_paper_s_example_with_and_without_lost_samples(guiro):
    system, data = guiro
    gains = adaptobs.design_guiro_gains(system["E"], system["C"], system["H0"], system["poles"])
    observer = make_observer(system, gains.K, gains.Gamma)
    result = observer.run(None, data["Y"], data["Psi"])
    assert np.all(result.status == UpdateStatus.accepted)
    assert abs(result.parameters[150, 0] - 5.0) < 1e-6
    # The corrected estimate z_{k-1} after the last sample is the estimate of its state.
    assert np.linalg.norm(observer.corrected_state - data["X"][-1]) < 1e-6
    present = np.random.default_rng(3).random((200, 1)) > 0.3
    lossy = make_observer(system, gains.K, gains.Gamma).run(None, data["Y"], data["Psi"], present=present)
    assert abs(lossy.parameters[-1, 0] - 5.0) < 1e-6
    assert abs(lossy.parameters[20, 0] - 5.0) > abs(result.parameters[20, 0] - 5.0)


def test_a_pickled_guiro_observer_continues_bit_for_bit(guiro):
    system, data = guiro
    observer = make_observer(system, system["printed_K"].reshape(2, 1), [[system["printed_Gamma"]]])
    observer.run(None, data["Y"][:5], data["Psi"][:5])
    twin = pickle.loads(pickle.dumps(observer))
    a = observer.run(None, data["Y"][5:], data["Psi"][5:])
    b = twin.run(None, data["Y"][5:], data["Psi"][5:])
    assert np.array_equal(a.parameters, b.parameters) and np.array_equal(a.state, b.state)
    assert np.array_equal(observer.corrected_state, twin.corrected_state)


def test_bad_gains_name_the_argument(guiro):
    system, _ = guiro
    with pytest.raises(ConfigurationError, match="GuiroObserver: argument 'Gamma' must be 1x1 \\(got 2x1\\)"):
        make_observer(system, np.zeros((2, 1)), np.zeros((2, 1)))
    observer = make_observer(system, np.zeros((2, 1)), np.zeros((1, 1)))
    with pytest.raises(ConfigurationError, match="GuiroObserver::set_gains: argument 'K'"):
        observer.set_gains(np.full((2, 1), np.nan), np.zeros((1, 1)))


def test_the_replay_matches_the_cxx_example(tmp_path):
    """The C++ example (examples/guiro.cpp, 60 samples on the regular grid, designed gains): the same
    theta_k before each update and the same corrected estimates z_{k-1} after it, to 1e-12."""
    table = cxx_example_table(tmp_path, "guiro")
    system = adaptobs.examples.guiro()
    data = adaptobs.examples.simulate_guiro(len(table))
    assert np.max(np.abs(data["Y"][:, 0] - table["y_1"])) < 1e-12
    gains = adaptobs.design_guiro_gains(system["E"], system["C"], system["H0"], system["poles"])
    observer = make_observer(system, gains.K, gains.Gamma)
    theta_before, corrected = [], []
    for k in range(len(table)):
        theta_before.append(observer.parameters[0])
        assert observer.update(None, data["Y"][k], data["Psi"][k]) == UpdateStatus.accepted
        corrected.append(observer.corrected_state)
    corrected = np.array(corrected)
    assert np.max(np.abs(np.array(theta_before) - table["thetahat_1"])) < 1e-12
    assert np.max(np.abs(corrected[:, 0] - table["xhat_1"])) < 1e-12
    assert np.max(np.abs(corrected[:, 1] - table["xhat_2"])) < 1e-12
    assert abs(table["thetahat_1"][-1] - 5.0) < 1e-6  # the paper's theta
