"""Bad input, the Python way: ConfigurationError (a ValueError) naming the
argument and both shapes; TypeError for what NumPy cannot read as numbers."""

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError
from conftest import make_observer


def test_configuration_error_is_a_value_error():
    assert issubclass(ConfigurationError, ValueError)


@pytest.mark.parametrize(
    "change, message",
    [
        ({"K": np.zeros((2, 4))}, "GuyaderZhangObserver: argument 'K' must be 4x2 (got 2x4)"),
        ({"mu": -1.0}, "GuyaderZhangObserver: argument 'mu' must be positive"),
        ({"x0": np.zeros(3)}, "GuyaderZhangObserver: argument 'x0'"),
        ({"theta0": np.zeros((2, 2))}, "GuyaderZhangObserver: argument 'theta0' must be a vector (a 1-D array) (got 2x2)"),
        ({"K": np.full((4, 2), np.nan)}, "GuyaderZhangObserver: argument 'K'"),
        ({"excitation_window": -1}, "GuyaderZhangObserver: argument 'options.excitation_window' must be non-negative"),
    ],
)
def test_guyader_zhang_constructor_names_the_bad_argument(satellite, change, message):
    system, _ = satellite
    arguments = {"K": system["K"], "mu": 4.0, "x0": system["x0_estimate"], "theta0": system["theta0_estimate"]}
    options = {k: change.pop(k) for k in list(change) if k == "excitation_window"}
    arguments.update(change)
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)
    with pytest.raises(ConfigurationError, match=None) as error:
        adaptobs.GuyaderZhangObserver(model, **arguments, **options)
    assert str(error.value).startswith(message), str(error.value)


@pytest.mark.parametrize(
    "arguments, message",
    [
        ((np.eye(3), np.zeros((4, 1)), np.zeros((1, 3)), 1), "DiscreteLtiModel: argument 'B' must be 3x1 (got 4x1)"),
        ((np.ones((2, 3)), np.zeros((2, 1)), np.zeros((1, 2)), 1), "DiscreteLtiModel: argument 'A' must be square"),
        ((np.eye(2), np.zeros((2, 1)), np.zeros((1, 2)), -1), "DiscreteLtiModel: argument 'np'"),
    ],
)
def test_the_model_names_the_bad_argument(arguments, message):
    with pytest.raises(ConfigurationError) as error:
        adaptobs.DiscreteLtiModel(*arguments)
    assert str(error.value).startswith(message), str(error.value)


def test_the_augmented_kalman_filter_names_the_bad_covariance(satellite):
    system, _ = satellite
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)
    with pytest.raises(ConfigurationError, match="AugmentedKalmanFilter: argument 'covariances.R'"):
        adaptobs.AugmentedKalmanFilter(model, system["x0_estimate"], system["theta0_estimate"],
                                       P0=np.eye(6), Q=np.zeros((6, 6)), R=-np.eye(2))


def test_wrong_sample_shapes_name_the_argument_and_both_shapes_and_change_nothing(satellite):
    system, data = satellite
    observer = make_observer(system)
    observer.run(data["U"][:50], data["Y"][:50], data["Psi"][:50])
    before = observer.snapshot()
    cases = [
        (lambda: observer.update([1.0, 2.0, 3.0], [0, 0], data["Psi"][0]),
         "GuyaderZhangObserver.update: argument 'u' must be (2,) (got (3,))"),
        (lambda: observer.update([1.0, 2.0], [0, 0], np.zeros((2, 4))),
         "GuyaderZhangObserver.update: argument 'Psi' must be 4x2 (got 2x4)"),
        (lambda: observer.update([1.0, 2.0], [0, 0], data["Psi"][0], present=[True]),
         "GuyaderZhangObserver.update: argument 'present' must be (2,) (got (1,))"),
        (lambda: observer.run(data["U"][:9], data["Y"][:10], data["Psi"][:10]),
         "GuyaderZhangObserver.run: argument 'U' must be 10x2 (samples x 2) (got 9x2)"),
        (lambda: observer.run(data["U"][:10], data["Y"][:10], data["Psi"][:9]),
         "GuyaderZhangObserver.run: argument 'Psi' must be (10, 4, 2) or 4x2 (got (9, 4, 2))"),
        (lambda: observer.run(data["U"][:10], data["Y"][:10], data["Psi"][:10], present=np.ones((10, 3), bool)),
         "GuyaderZhangObserver.run: argument 'present' must be 10x2 (got 10x3)"),
        (lambda: observer.run(None, data["Y"][:10]),
         "GuyaderZhangObserver.run: argument 'U' is required"),
    ]
    for call, message in cases:
        with pytest.raises(ConfigurationError) as error:
            call()
        assert str(error.value).startswith(message), str(error.value)
    after = observer.snapshot()
    assert before["integers"] == after["integers"]
    for name in before["matrices"]:
        assert np.array_equal(before["matrices"][name], after["matrices"][name])


def test_what_numpy_cannot_read_as_numbers_is_a_type_error_naming_the_argument(satellite):
    system, _ = satellite
    observer = make_observer(system)
    with pytest.raises(TypeError, match="GuyaderZhangObserver.update: argument 'y' must be an array of real numbers"):
        observer.update([0.0, 0.0], ["a", "b"], None)
    with pytest.raises(TypeError, match="DiscreteLtiModel: argument 'A' must be an array of real numbers"):
        adaptobs.DiscreteLtiModel({"not": "a matrix"}, np.zeros((1, 1)), np.zeros((1, 1)), np=0)


def test_lists_and_integer_arrays_are_converted_once(satellite):
    system, data = satellite
    a, b = make_observer(system), make_observer(system)
    psi = data["Psi"][0]
    assert a.update([1, 0], [1, 0], psi.tolist()) == b.update(np.array([1.0, 0.0]), np.array([1.0, 0.0]), psi)
    assert np.array_equal(a.state, b.state)


def test_complex_and_object_arrays_are_refused_not_truncated(satellite):
    system, data = satellite
    observer = make_observer(system)
    with pytest.raises(TypeError, match="GuyaderZhangObserver.run: argument 'Y' must be an array of real numbers"):
        observer.run(data["U"][:5], data["Y"][:5] + 1j, data["Psi"][:5])
    with pytest.raises(TypeError, match="argument 'present' must be an array of booleans"):
        observer.update([0.0, 0.0], [0.0, 0.0], data["Psi"][0], present=[1.5, 0.0])
    assert observer.step == 0


def test_a_model_of_the_wrong_type_is_a_type_error_naming_it(satellite):
    system, _ = satellite
    with pytest.raises(TypeError, match="GuyaderZhangObserver: argument 'model' must be an adaptobs.DiscreteLtiModel"):
        adaptobs.GuyaderZhangObserver(system, system["K"], 4.0, system["x0_estimate"], system["theta0_estimate"])


def test_a_missing_regressor_is_refused_when_the_model_has_parameters(satellite):
    system, data = satellite
    observer = make_observer(system)
    with pytest.raises(ConfigurationError, match="GuyaderZhangObserver.update: argument 'Psi' is required"):
        observer.update(data["U"][0], data["Y"][0])
    with pytest.raises(ConfigurationError, match="GuyaderZhangObserver.run: argument 'Psi' is required"):
        observer.run(data["U"][:3], data["Y"][:3])


def test_a_model_pickles_and_a_malformed_snapshot_names_its_key(satellite):
    import pickle

    system, _ = satellite
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)
    twin = pickle.loads(pickle.dumps(model))
    assert np.array_equal(twin.A, model.A) and twin.sizes == model.sizes
    observer = make_observer(system)
    state = observer.snapshot()
    state["version"] = "one"
    with pytest.raises(TypeError, match="restore: argument 'state\\['version'\\]' must be an int"):
        observer.restore(state)
    state = observer.snapshot()
    state["matrices"] = []
    with pytest.raises(TypeError, match="restore: argument 'state\\['matrices'\\]' must be a dict"):
        observer.restore(state)


def test_scalar_arguments_take_numpy_scalars_and_name_the_wrong_kind(satellite):
    system, _ = satellite
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=np.int64(2))
    observer = adaptobs.GuyaderZhangObserver(model, system["K"], np.float64(4.0), system["x0_estimate"],
                                             system["theta0_estimate"], excitation_window=np.int32(10),
                                             normalized_step=np.True_)
    assert observer.mu == 4.0
    cases = [
        (TypeError, dict(excitation_window=10.0), "argument 'excitation_window' must be an integer (got float)"),
        (TypeError, dict(normalized_step="yes"), "argument 'normalized_step' must be a bool (got str)"),
        (TypeError, dict(mu=True), "argument 'mu' must be a real number (got bool)"),
        (ConfigurationError, dict(mu=np.array([4.0])), "argument 'mu' must be a scalar (got (1,))"),
    ]
    for error_type, change, message in cases:
        arguments = {"mu": 4.0, **change}
        with pytest.raises(error_type) as error:
            adaptobs.GuyaderZhangObserver(model, system["K"], x0=system["x0_estimate"],
                                          theta0=system["theta0_estimate"], **arguments)
        assert str(error.value) == "GuyaderZhangObserver: " + message
