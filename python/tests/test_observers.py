"""The observers from Python: run() against a loop of update(), rejected
samples, masks, convergence, and the C++ example's estimates."""

import sys
import threading

import numpy as np
import pytest

import adaptobs
from adaptobs import UpdateStatus
from conftest import cxx_example_table, make_filter, make_observer, step_by_step


def test_update_status_is_an_int_enum():
    assert int(UpdateStatus.accepted) == 0
    assert UpdateStatus(1) is UpdateStatus.nonfinite_input
    assert isinstance(UpdateStatus.nonfinite_result, int)


@pytest.mark.parametrize("make", [make_observer, make_filter])
def test_run_equals_a_loop_of_update_bit_for_bit_with_masks_and_rejections(satellite, make):
    system, data = satellite
    U, Y, Psi = data["U"][:800], data["Y"][:800].copy(), data["Psi"][:800]
    rng = np.random.default_rng(7)
    present = rng.random((800, 2)) > 0.3
    Y[100, 0] = np.nan  # rejected unless channel 0 is absent at 100
    present[100, 0] = True
    Y[200, 1] = np.inf
    present[200, 1] = False  # absent: ignored, the sample is accepted
    a, b = make(system), make(system)
    result = a.run(U, Y, Psi, present=present)
    x, theta, error, status = step_by_step(b, U, Y, Psi, present)
    assert np.array_equal(result.state, x)
    assert np.array_equal(result.parameters, theta)
    assert np.array_equal(result.output_error, error)
    assert np.array_equal(result.status, status)
    assert result.status[100] == UpdateStatus.nonfinite_input
    assert result.status[200] == UpdateStatus.accepted
    assert np.count_nonzero(result.status) == 1
    assert np.array_equal(a.state, b.state) and a.step == b.step == 799


def test_run_reads_every_layout_alike(satellite):
    """C order, Fortran order, strided views and lists give the same estimates."""
    system, data = satellite
    U, Y, Psi = data["U"][:500], data["Y"][:500], data["Psi"][:500]
    reference = make_observer(system).run(U, Y, Psi).parameters
    wide_u = np.zeros((500, 4))
    wide_u[:, ::2] = U  # a view with a column stride of 2
    layouts = [
        (np.asfortranarray(U), np.asfortranarray(Y), np.asfortranarray(Psi)),
        (wide_u[:, ::2], Y[:, :], np.transpose(np.transpose(Psi, (0, 2, 1)).copy(), (0, 2, 1))),
        (U.astype(np.float32) if np.all(U == U.astype(np.float32)) else U, Y.tolist(), Psi),
    ]
    for u, y, psi in layouts:
        assert np.array_equal(make_observer(system).run(u, y, psi).parameters, reference)
    # A constant regressor given once equals it repeated for every sample.
    constant = make_observer(system).run(U, Y, Psi[10]).parameters
    repeated = make_observer(system).run(U, Y, np.repeat(Psi[10:11], 500, axis=0)).parameters
    assert np.array_equal(constant, repeated)


def test_a_rejected_sample_leaves_the_observer_bit_identical(satellite):
    system, data = satellite
    observer = make_observer(system, excitation_window=50)
    observer.run(data["U"][:300], data["Y"][:300], data["Psi"][:300])
    before = observer.snapshot()
    assert observer.update([np.nan, 0.0], data["Y"][300], data["Psi"][300]) == UpdateStatus.nonfinite_input
    assert observer.update(data["U"][300], [0.0, np.inf], data["Psi"][300]) == UpdateStatus.nonfinite_input
    # Finite, but the step would overflow: Upsilon_{k+1} (theta_{k+1} - theta_k) is about 1e600.
    huge = observer.update(data["U"][300], [1e300, 1e300], np.full((4, 2), 1e300))
    assert huge == UpdateStatus.nonfinite_result
    after = observer.snapshot()
    # Only the health record notes the overflowing step (one refusal, not yet a divergence).
    assert after["integers"].pop("health.consecutive_refusals") == 1
    assert after["integers"].pop("health.streak_step") == 300
    assert before["integers"].pop("health.consecutive_refusals") == 0
    assert before["integers"].pop("health.streak_step") == -1
    assert before["integers"] == after["integers"]
    for name, value in before["matrices"].items():
        assert np.array_equal(value, after["matrices"][name]), name


def test_guyader_zhang_converges_on_the_noise_free_satellite():
    system = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(3000, noise=0.0)
    observer = make_observer(system, excitation_window=100)
    result = observer.run(data["U"], data["Y"], data["Psi"])
    assert np.linalg.norm(result.parameters[-1] - system["theta"]) < 1e-6
    # State after sample k is the estimate of x_{k+1}.
    assert np.linalg.norm(result.state[-2] - data["X"][-1]) < 1e-6
    assert observer.excitation_level > 0.0
    assert np.all(result.diagnostics["assumption2_norm"] <= 1.0)
    assert np.isnan(result.diagnostics["excitation_level"][0])  # the window has not filled


def test_the_augmented_kalman_filter_converges_on_the_satellite(satellite):
    system, data = satellite
    result = make_filter(system).run(data["U"], data["Y"], data["Psi"])
    assert np.all(result.status == UpdateStatus.accepted)
    assert np.linalg.norm(result.parameters[-300:].mean(axis=0) - system["theta"]) < 0.01


def test_the_satellite_replay_matches_the_cxx_example(tmp_path):
    """The C++ example's CSV (same plant, same seed) against the Python run, to 1e-12."""
    table = cxx_example_table(tmp_path, "satellite")
    system = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(len(table), noise=0.01, seed=2003)
    assert np.array_equal(data["Y"][:, 0], table["y_1"])
    result = make_observer(system, excitation_window=100).run(data["U"], data["Y"], data["Psi"])
    cxx = np.column_stack([table["thetahat_1"], table["thetahat_2"]])
    # Row k of the CSV holds the estimates before sample k, the run's row k those after it.
    assert np.max(np.abs(result.parameters[:-1] - cxx[1:])) <= 1e-12
    cxx_state = np.column_stack([table[f"xhat_{i}"] for i in range(1, 5)])
    assert np.max(np.abs(result.state[:-1] - cxx_state[1:])) <= 1e-12
    akf = make_filter(system)
    akf_result = akf.run(data["U"], data["Y"], data["Psi"])
    cxx_akf = np.column_stack([table["thetahat_akf_1"], table["thetahat_akf_2"]])
    assert np.max(np.abs(akf_result.parameters[:-1] - cxx_akf[1:])) <= 1e-12


def test_run_releases_the_gil():
    """While one thread runs 10^6 samples, another thread executes Python code.

    The switch interval is made tiny, so that a thread holding the GIL through
    the loop would leave the other only a few ticks between the start of run()
    and its end; with the GIL released the other thread runs all along."""
    system = adaptobs.examples.satellite()
    n = 1_000_000
    U = np.zeros((n, 2))
    Y = np.zeros((n, 2))
    observer = make_observer(system)
    started = threading.Event()
    done = threading.Event()

    def work():
        started.set()
        observer.run(U, Y, np.zeros((4, 2)))  # one regressor for every sample
        done.set()

    ticks = 0
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        thread = threading.Thread(target=work)
        thread.start()
        started.wait()
        while not done.is_set():
            ticks += 1
        thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert observer.step == n
    # With the GIL held through the loop this thread would run only between switch intervals.
    assert ticks > 10_000


def test_one_observer_used_from_two_threads_is_refused_not_corrupted():
    """While run() holds the observer (GIL released), a call from another thread is a RuntimeError."""
    system = adaptobs.examples.satellite()
    observer = make_observer(system)
    n = 2_000_000
    U, Y = np.zeros((n, 2)), np.zeros((n, 2))
    started = threading.Event()
    errors = []

    def work():
        started.set()
        observer.run(U, Y, np.zeros((4, 2)))

    thread = threading.Thread(target=work)
    thread.start()
    started.wait()
    state = observer.snapshot()
    while thread.is_alive():
        try:
            observer.restore(state)
        except RuntimeError as error:
            errors.append(str(error))
            break
    thread.join()
    assert errors and "in use by a call on another thread" in errors[0]
    assert observer.step == n  # the run went through untouched


def test_a_known_input_term_enters_update_and_run():
    """Remark 1 of Guyader & Zhang (2003): f_k of the measured u_k and y_k is added to the state's
    step. On the noise-free satellite driven by it, run() with known_input equals a loop of update()
    bit for bit and converges; without it, theta_hat settles about 1e-3 away."""
    system = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(3000, noise=0.0)
    A, C, U, Psi = system["A"], system["C"], data["U"], data["Psi"]
    x = np.array(data["X"][0])
    Y, F = np.zeros((3000, 2)), np.zeros((3000, 4))
    for k in range(3000):
        Y[k] = C @ x
        F[k] = [0.0, 1e-3 * np.sin(Y[k, 0]), 0.0, 1e-4 * np.cos(0.01 * k) * (1 + U[k, 0])]
        x = A @ x + F[k] + Psi[k] @ system["theta"]
    observer, loop = make_observer(system), make_observer(system)
    result = observer.run(U, Y, Psi, known_input=F)
    for k in range(3000):
        assert loop.update(U[k], Y[k], Psi[k], known_input=F[k]) == UpdateStatus.accepted
    assert np.array_equal(result.parameters[-1], loop.parameters)
    assert np.array_equal(result.state[-1], loop.state)
    assert np.linalg.norm(result.parameters[-1] - system["theta"]) < 1e-9
    assert np.linalg.norm(result.state[-1] - x) < 1e-9
    without = make_observer(system).run(U, Y, Psi).parameters[-1]
    assert np.linalg.norm(without - system["theta"]) > 1e-4
    with pytest.raises(adaptobs.ConfigurationError, match="known_input"):
        make_observer(system).update(U[0], Y[0], Psi[0], known_input=np.zeros(3))
    with pytest.raises(adaptobs.ConfigurationError, match="known_input"):
        make_observer(system).run(U, Y, Psi, known_input=F[:, :3])
    bad = make_observer(system)
    assert bad.update(U[0], Y[0], Psi[0], known_input=[0.0, np.nan, 0.0, 0.0]) == UpdateStatus.nonfinite_input
    assert bad.step == 0
