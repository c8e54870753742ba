"""Choosing mu from the regressors (guyader_zhang_mu_bound, _convergence,
_fastest_mu) and what health() reports, from Python."""

import pickle

import numpy as np
import pytest

import adaptobs
from adaptobs import Health


def _model(system):
    return adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)


def _observer(system, mu):
    return adaptobs.GuyaderZhangObserver(
        _model(system), system["K"], mu, system["x0_estimate"], system["theta0_estimate"]
    )


def test_the_mu_bound_is_where_assumption_two_starts_to_fail(satellite):
    system, data = satellite
    Psi = data["Psi"][:1000]
    bound = adaptobs.guyader_zhang_mu_bound(_model(system), system["K"], Psi)
    # The paper's mu = 4 is just below it (with every output present).
    assert 4.0 < bound < 5.0
    for factor, state in ((0.99, Health.healthy), (1.01, Health.assumption_violated)):
        observer = _observer(system, factor * bound)
        result = observer.run(data["U"][:1000], data["Y"][:1000], Psi)
        largest = np.max(result.diagnostics["assumption2_norm"])
        assert largest**2 == pytest.approx(factor, rel=1e-9)
        assert observer.health.state == state, observer.health.message


def test_a_diverging_observer_says_so_and_the_record_survives_pickling(satellite):
    system, data = satellite
    observer = _observer(system, 400.0)
    result = observer.run(data["U"], data["Y"], data["Psi"])
    health = observer.health
    assert health.state == Health.diverged
    assert np.count_nonzero(result.status == adaptobs.UpdateStatus.nonfinite_result) > 100
    assert health.step == observer.step
    assert health.message.startswith("diverged: assumption 2")
    assert "ran away" in health.message
    copy = pickle.loads(pickle.dumps(observer))
    assert copy.health.message == health.message
    copy.reset(system["x0_estimate"], system["theta0_estimate"])
    assert copy.health.state == Health.healthy and copy.health.step == -1


def test_the_predicted_rate_matches_the_noise_free_observer(satellite):
    system, _ = satellite
    data = adaptobs.examples.simulate_satellite(3000, noise=0.0, seed=1)
    model = _model(system)
    bound = adaptobs.guyader_zhang_mu_bound(model, system["K"], data["Psi"])
    fastest = adaptobs.guyader_zhang_fastest_mu(model, system["K"], data["Psi"])
    assert 0 < fastest["mu"] <= bound
    slow = adaptobs.guyader_zhang_convergence(model, system["K"], data["Psi"], 0.05 * bound)
    assert fastest["rate"] < slow["rate"] < 1
    observer = _observer(system, 0.05 * bound)
    result = observer.run(data["U"], data["Y"], data["Psi"])
    error = np.linalg.norm(result.parameters - np.array([1.0, 1.5]), axis=1)
    # Over whole periods of the thrust pulses (100 steps), after the transient.
    measured = np.log(error[1999] / error[999]) / 1000
    assert measured == pytest.approx(np.log(slow["rate"]), rel=0.02)


def test_tuning_refuses_bad_regressors_naming_them(satellite):
    system, _ = satellite
    with pytest.raises(adaptobs.ConfigurationError, match="guyader_zhang_mu_bound: argument 'Psi'"):
        adaptobs.guyader_zhang_mu_bound(_model(system), system["K"], np.zeros((4, 2)))
    with pytest.raises(adaptobs.ConfigurationError, match="argument 'regressors'.*never reach the output"):
        adaptobs.guyader_zhang_mu_bound(_model(system), system["K"], np.zeros((10, 4, 2)))
