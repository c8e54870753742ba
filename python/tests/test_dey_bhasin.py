"""The observers of Dey & Bhasin (2022) from Python: the MIMO example of its
section 5 identified, the C++ example's estimates to 1e-12, batch against
step, pickling, and refusals."""

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import assert_update_follows_run, cxx_example_table


def make_dey_bhasin(system):
    return adaptobs.DeyBhasinObserver(system["f"], system["x0_estimate"], system["a0_estimate"],
                                      system["B0_estimate"], k0=system["k0"], kmin=system["kmin"], R=system["R"])


def make_suzuki(system):
    return adaptobs.SuzukiObserver(system["f"], system["x0_estimate"], system["a0_estimate"], system["B0_estimate"],
                                   gamma0=np.eye(15) * 1000.0, R=system["R"], lambda_=0.98)


@pytest.fixture(scope="module")
def mimo():
    return adaptobs.examples.dey_bhasin_mimo(), adaptobs.examples.simulate_dey_bhasin_mimo(400)


def test_every_entry_of_a_and_b_is_identified_with_a_rich_input(mimo):
    system, data = mimo
    observer = make_dey_bhasin(system)
    result = observer.run(data["U"], data["Y"])
    assert np.all(result.status == UpdateStatus.accepted)
    assert np.max(np.abs(observer.a_hat / system["a"] - 1)) < 1e-6
    assert np.max(np.abs(observer.B_hat / system["B"] - 1)) < 1e-6
    # x_hat_{t+1|t} against the true state of step t + 1.
    assert np.linalg.norm(result.state[-2] - data["X"][-1]) < 1e-6
    assert observer.reset_count == result.diagnostics["reset_count"][-1] > 0
    p = np.concatenate([system["a"] - system["f"], system["B"].reshape(-1, order="F")])
    assert np.max(np.abs(result.parameters[-1] - p)) < 1e-6


def test_an_input_that_is_not_rich_leaves_the_estimates_wrong(mimo):
    system, _ = mimo
    data = adaptobs.examples.simulate_dey_bhasin_mimo(400, rich=False)
    observer = make_dey_bhasin(system)
    observer.run(data["U"], data["Y"])
    assert np.max(np.abs(observer.B_hat / system["B"] - 1)) > 0.05


def test_the_mimo_replay_matches_the_cxx_example(tmp_path, mimo):
    table = cxx_example_table(tmp_path, "dey_bhasin_mimo", csv="dey_bhasin_mimo_pe.csv")
    system, _ = mimo
    data = adaptobs.examples.simulate_dey_bhasin_mimo(len(table))
    assert np.array_equal(data["Y"][:, 1], table["y_2"])
    observer = make_dey_bhasin(system)
    result = observer.run(data["U"], data["Y"])
    cxx = np.column_stack([table[f"thetahat_{i}"] for i in range(1, 16)])
    assert np.max(np.abs(result.parameters - cxx)) <= 1e-12 * max(1.0, np.max(np.abs(cxx)))
    assert np.array_equal(result.diagnostics["reset_count"], table["resets"])


@pytest.mark.parametrize("make", [make_dey_bhasin, make_suzuki])
def test_run_equals_update_and_copies_continue_bit_for_bit(mimo, make):
    system, data = mimo
    U, Y = data["U"], data["Y"].copy()
    present = np.ones(Y.shape, bool)
    present[50:60, 1] = False
    Y[50:60, 1] = np.nan  # absent: ignored
    Y[120, 0] = np.inf  # present: the sample is rejected
    result, batch, stepped = assert_update_follows_run(lambda: make(system), U, Y, present,
                                                       {150: "pickle", 250: "deepcopy"})
    assert result.status[120] == UpdateStatus.nonfinite_input
    assert np.count_nonzero(result.status) == 1
    assert np.array_equal(stepped.covariance, batch.covariance)


def test_a_suzuki_snapshot_is_not_a_dey_bhasin_one(mimo):
    system, _ = mimo
    with pytest.raises(ConfigurationError, match="is of a SuzukiObserver, not of a DeyBhasinObserver"):
        make_dey_bhasin(system).restore(make_suzuki(system).snapshot())


def test_bad_arguments_name_the_argument(mimo):
    system, data = mimo
    cases = [
        (lambda: adaptobs.DeyBhasinObserver(system["f"], np.zeros(5), system["a0_estimate"], system["B0_estimate"],
                                            k0=1000.0, kmin=1e-4, R=np.eye(2)), "DeyBhasinObserver: argument 'x0'"),
        (lambda: adaptobs.DeyBhasinObserver(system["f"], system["x0_estimate"], system["a0_estimate"],
                                            system["B0_estimate"], k0=1000.0, kmin=2000.0, R=np.eye(2)),
         "CovarianceResettingRls: argument 'kmin' must be smaller than k0"),
        (lambda: adaptobs.SuzukiObserver(system["f"], system["x0_estimate"], system["a0_estimate"],
                                         system["B0_estimate"], gamma0=np.eye(15), R=np.eye(2), lambda_=1.5),
         "ExponentialForgettingRls: argument 'lambda'"),
        (lambda: make_dey_bhasin(system).update([0.0, 0.0], [0.0, 0.0], np.zeros((6, 15))),
         "DeyBhasinObserver.update: argument 'Psi' must be None"),
        (lambda: make_dey_bhasin(system).run(data["U"][:10], data["Y"][:11]),
         "DeyBhasinObserver.run: argument 'U' must be 11x2 (samples x 2) (got 10x2)"),
    ]
    for call, message in cases:
        with pytest.raises(ConfigurationError) as error:
            call()
        assert str(error.value).startswith(message), str(error.value)


def test_on_the_siso_comparison_forgetting_overflows_and_resetting_does_not():
    """Section 5, figures 4-5: u_t = sin 0.2t excites two of the four directions. Suzuki's forgetting
    grows Gamma by 1/lambda a step until it overflows; the observer then rejects every step
    (nonfinite_result) and keeps its last estimates. Covariance resetting keeps Gamma in [kmin, k0]."""
    s = adaptobs.examples.dey_bhasin_siso()
    data = adaptobs.examples.simulate_dey_bhasin_siso(3000)
    resetting = adaptobs.DeyBhasinObserver(s["f"], s["x0_estimate"], s["a0_estimate"], s["B0_estimate"],
                                           k0=s["k0"], kmin=s["kmin"], R=s["R"])
    suzuki = adaptobs.SuzukiObserver(s["f"], s["x0_estimate"], s["a0_estimate"], s["B0_estimate"],
                                     gamma0=s["k0"] * np.eye(4), R=s["R"], lambda_=s["lambda"])
    kept = resetting.run(data["U"], data["Y"])
    forgot = suzuki.run(data["U"], data["Y"])
    assert np.all(kept.status == UpdateStatus.accepted)
    assert np.all(np.isfinite(kept.parameters)) and np.all(np.isfinite(kept.state))
    rejected = np.flatnonzero(forgot.status != UpdateStatus.accepted)
    # Gamma ~ k0 * 2^(t/2) passes the largest double (1.8e308) near t = 2 log2(1.8e308 / 1e4) = 2021.
    assert 1900 < rejected[0] < 2200
    assert np.all(forgot.status[rejected[0]:] == UpdateStatus.nonfinite_result)
    assert np.array_equal(forgot.parameters[-1], forgot.parameters[rejected[0] - 1])


def test_the_excitation_diagnostics_of_definition_1(mimo):
    # I_t = sum phi_i R^-1 phi_i^T and the window of the last 100 samples, t = 0..1000
    # (figures of tests/test_dey_bhasin_mimo.cpp and docs/readings/dey_bhasin.md).
    import pickle

    system, _ = mimo
    data = adaptobs.examples.simulate_dey_bhasin_mimo(1001)
    observer = adaptobs.DeyBhasinObserver(system["f"], system["x0_estimate"], system["a0_estimate"],
                                          system["B0_estimate"], k0=system["k0"], kmin=system["kmin"],
                                          R=system["R"], information=True, excitation_window=100)
    assert observer.excitation_level is None and observer.excitation_rank is None
    observer.run(data["U"], data["Y"])
    assert observer.information_level == pytest.approx(6.1682, abs=1e-4)
    assert observer.information.shape == (15, 15)
    assert observer.excitation_level == pytest.approx(5.662e-3, abs=1e-6)
    assert observer.excitation_rank == 15
    copy = pickle.loads(pickle.dumps(observer))
    assert copy.information_level == observer.information_level
    assert copy.excitation_rank == 15
    plain = make_dey_bhasin(system)
    plain.run(data["U"][:10], data["Y"][:10])
    assert plain.information is None and plain.information_level is None and plain.excitation_level is None
    with pytest.raises(ConfigurationError, match="excitation_window"):
        adaptobs.DeyBhasinObserver(system["f"], system["x0_estimate"], system["a0_estimate"], system["B0_estimate"],
                                   k0=system["k0"], kmin=system["kmin"], R=system["R"], excitation_window=-1)
