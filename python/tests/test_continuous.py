"""The continuous-time observers of the unified formulation (Zhang 2005) from
Python on the third-order plant: Bastin-Gevers and Marino-Tomei against the
C++ examples' estimates, all four converging, batch against step, pickling
with a callable regressor, garbage collection of a regressor cycle, and
refusals."""

import copy
import pathlib
import pickle
import sys

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import assert_matches_recorded_samples, cxx_example_table


sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))
from unified import bastin_gevers, besancon, kalman_bucy, marino_tomei, model, regressor, run, zhang  # noqa: E402


@pytest.fixture(scope="module")
def siso():
    return adaptobs.examples.siso(), adaptobs.examples.simulate_siso(10001)


@pytest.mark.parametrize("make", [bastin_gevers, marino_tomei, besancon, zhang, kalman_bucy])
def test_theta_and_the_state_converge(siso, make):
    system, data = siso
    observer = make(system)
    result = run(observer, data)
    assert np.all(result.status == UpdateStatus.accepted)
    # The Kalman-Bucy filter's theta random-walk density (1e-2) keeps it 3e-3 off at 100 s.
    tolerance = 1e-2 if make is kalman_bucy else 1e-3
    assert np.linalg.norm(result.parameters[-1] - system["theta"]) < tolerance
    assert np.linalg.norm(result.state[-1] - data["X"][-1]) < tolerance
    assert observer.time == pytest.approx(100.0)


@pytest.mark.parametrize("make, name", [(bastin_gevers, "bastin_gevers"), (marino_tomei, "marino_tomei")])
def test_the_replay_matches_the_cxx_example(tmp_path, siso, make, name):
    table = cxx_example_table(tmp_path, name)
    system, data = siso
    assert_matches_recorded_samples(table, data, run(make(system), data), every=10, states=3)


@pytest.mark.parametrize("make", [bastin_gevers, marino_tomei, besancon, zhang, kalman_bucy])
def test_run_equals_update_and_copies_continue_bit_for_bit(siso, make):
    system, data = siso
    n = 600
    options = {} if make is kalman_bucy else {"excitation_window": 50}
    batch = make(system, **options)
    result = run(batch, data, n)
    stepped = make(system, **options)
    for k in range(n):
        if k == 200:
            stepped = pickle.loads(pickle.dumps(stepped))
        if k == 400:
            stepped = copy.deepcopy(stepped)
        mid = (None, None) if k == 0 else (data["U_mid"][k], data["Y_mid"][k])
        assert stepped.update(data["t"][k], data["U"][k], data["Y"][k], *mid) == UpdateStatus.accepted
        assert np.array_equal(stepped.parameters, result.parameters[k]), k
        assert np.array_equal(stepped.state, result.state[k]), k
    assert np.array_equal(stepped.internal_state, batch.internal_state)
    if make is kalman_bucy:
        assert np.array_equal(stepped.covariance, batch.covariance) and stepped.excitation_level is None
    else:
        assert stepped.excitation_level == batch.excitation_level > 0


@pytest.mark.parametrize("make", [bastin_gevers, zhang, kalman_bucy])
def test_an_output_outage_is_the_time_update(siso, make):
    # 6 s without y (NaN, never read) in the 100-s run: theta-hat holds still over the outage
    # and its error after it stays within a small factor of the error before it.
    system, data = siso
    n, start, stop = 8000, 5000, 5600
    present = np.ones((n, 1), dtype=bool)
    present[start:stop] = False
    Y, Y_mid = data["Y"][:n].copy(), data["Y_mid"][:n].copy()
    Y[start:stop] = np.nan
    Y_mid[start:stop] = np.nan
    observer = make(system)
    result = observer.run(data["t"][:n], data["U"][:n], Y, data["U_mid"][:n], Y_mid, present)
    assert np.all(result.status == UpdateStatus.accepted)
    # The interval that ends the outage starts without y: theta-hat moves again one sample later.
    held = result.parameters[start - 1:stop + 1]
    assert np.array_equal(held, np.broadcast_to(result.parameters[start - 1], held.shape))
    assert not np.array_equal(result.parameters[stop + 1], result.parameters[stop])
    assert np.all(result.output_error[start:stop] == 0)
    error = np.linalg.norm(result.parameters - system["theta"], axis=1)
    assert error[stop + 10] < 5 * error[start - 1]
    # Stepped with the same masks: the same estimates, bit for bit.
    stepped = make(system)
    for k in range(stop + 10):
        mid = (None, None) if k == 0 else (data["U_mid"][k], Y_mid[k])
        assert stepped.update(data["t"][k], data["U"][k], Y[k], *mid, present=present[k]) == UpdateStatus.accepted
    assert np.array_equal(stepped.parameters, result.parameters[stop + 9])


def test_a_rejected_sample_changes_nothing(siso):
    system, data = siso
    observer = bastin_gevers(system)
    run(observer, data, 100)
    before = observer.snapshot()
    t = data["t"][100]
    assert observer.update(t, [np.nan], data["Y"][100], data["U_mid"][100], data["Y_mid"][100]) == \
        UpdateStatus.nonfinite_input
    assert observer.update(data["t"][50], data["U"][100], data["Y"][100], data["U_mid"][100],
                           data["Y_mid"][100]) == UpdateStatus.nonincreasing_time
    after = observer.snapshot()
    assert before["integers"] == after["integers"]
    assert all(np.array_equal(before["matrices"][key], after["matrices"][key]) for key in before["matrices"])


def test_a_constant_regressor_never_calls_python_and_pickles(siso):
    system, data = siso
    constant = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    transform = adaptobs.bastin_gevers_form(system["A"], system["C"], [1.0, 4.0, 3.0])
    so = transform.apply(system["A"], system["B"], system["C"])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], [1.0, 0.0, 0.0], 2.0)
    m = adaptobs.ContinuousLtiModel(system["A"], system["B"], system["C"], constant)
    observer = adaptobs.BastinGeversObserver(m, transform, k, np.eye(2), np.zeros(3), np.zeros(2))
    result = run(observer, data, 300)
    twin = pickle.loads(pickle.dumps(observer))
    assert np.array_equal(twin.parameters, result.parameters[-1])
    assert np.array_equal(m.Phi, constant)


def test_bad_arguments_name_the_argument(siso):
    system, data = siso
    transform = adaptobs.bastin_gevers_form(system["A"], system["C"], [1.0, 4.0, 3.0])
    cases = [
        (lambda: adaptobs.ContinuousLtiModel(system["A"], system["B"], system["C"], regressor),
         "ContinuousLtiModel: argument 'np' is required when Phi is a callable"),
        (lambda: adaptobs.ContinuousLtiModel(system["A"], system["B"], system["C"], lambda t: np.zeros((2, 2)), np=2),
         "ContinuousLtiModel: argument 'Phi' must be 3x2 (got 2x2)"),
        (lambda: adaptobs.bastin_gevers_form(system["A"], system["C"], [1.0, -4.0, 3.0]), "bastin_gevers_form"),
        (lambda: adaptobs.BastinGeversObserver(model(system), transform, np.zeros((3, 1)), np.eye(2), np.zeros(3),
                                               np.zeros(2), input="cubic"),
         "BastinGeversObserver: argument 'input' must be 'hold', 'linear' or 'quadratic' (got 'cubic')"),
        (lambda: bastin_gevers(system).update(0.0, [1.0], [0.0], [1.0], None),
         "BastinGeversObserver.update: argument 'y_mid' must be given with the other midpoint signal"),
        (lambda: adaptobs.spr_injection_gain(system["A"], system["C"], [1.0, 0.0, 0.0], -1.0),
         "spr_injection_gain: argument 'lambda'"),
    ]
    for call, message in cases:
        with pytest.raises(ConfigurationError) as error:
            call()
        assert str(error.value).startswith(message), str(error.value)
    # An exception raised by the regressor reaches the caller, the observer unchanged.
    calls = {"n": 0}

    def failing(t):
        calls["n"] += 1
        if calls["n"] > 3:
            raise RuntimeError("sensor table exhausted")
        return regressor(t)

    transform_bg = adaptobs.bastin_gevers_form(system["A"], system["C"], [1.0, 4.0, 3.0])
    so = transform_bg.apply(system["A"], system["B"], system["C"])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], [1.0, 0.0, 0.0], 2.0)
    observer = adaptobs.BastinGeversObserver(model(system, failing), transform_bg, k, np.eye(2), np.zeros(3),
                                             np.zeros(2))
    observer.update(0.0, data["U"][0], data["Y"][0])
    before = observer.internal_state
    with pytest.raises(RuntimeError, match="sensor table exhausted"):
        observer.run(data["t"][1:5], data["U"][1:5], data["Y"][1:5])
    assert np.array_equal(observer.internal_state, before) and observer.time == 0.0


def test_a_quadratic_reconstruction_without_midpoints_names_the_python_argument(siso):
    system, data = siso
    observer = zhang(system)
    with pytest.raises(ConfigurationError, match=r"run: argument 'U_mid' must be given, with Y_mid"):
        observer.run(data["t"][:5], data["U"][:5], data["Y"][:5])
    assert observer.time == 0.0 and not observer.internal_state.any()
    assert observer.update(data["t"][0], data["U"][0], data["Y"][0]) == UpdateStatus.accepted  # the time origin
    state = observer.internal_state
    with pytest.raises(ConfigurationError, match=r"update: argument 'u_mid' must be given, with y_mid"):
        observer.update(data["t"][1], data["U"][1], data["Y"][1])
    assert np.array_equal(observer.internal_state, state)


def test_a_cycle_through_the_regressor_is_collected(siso):
    """An observer stored where its regressor can reach it is freed by the garbage collector."""
    import gc
    import weakref

    system, data = siso

    class Holder:
        pass

    holder = Holder()

    def phi(t):
        holder.observer  # the closure keeps holder, and so the observer, alive
        return regressor(t)

    transform = adaptobs.marino_tomei_form(system["A"], system["C"])
    so = transform.apply(system["A"], system["B"], system["C"])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], [1.0, 3.0, 2.0], 5.0)
    holder.observer = None
    holder.observer = adaptobs.MarinoTomeiObserver(model(system, phi), transform, [1.0, 3.0, 2.0], k, np.eye(2),
                                                   np.zeros(3), np.zeros(2))  # phi -> holder -> observer -> phi
    run(holder.observer, data, 20)
    alive = weakref.ref(holder)
    del holder, phi
    gc.collect()
    assert alive() is None
