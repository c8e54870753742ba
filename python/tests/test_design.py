"""The design routines from Python, each checked against its defining
equation computed here in NumPy."""

import numpy as np
import pytest

import adaptobs


def test_solve_dare_satisfies_the_equation_and_stabilizes():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(4, 4))
    B = rng.normal(size=(4, 2))
    Q, R = np.eye(4), np.eye(2)
    solution = adaptobs.solve_dare(A, B, Q, R)
    X = solution.X
    gain = np.linalg.solve(R + B.T @ X @ B, B.T @ X @ A)
    residual = A.T @ X @ A - X - A.T @ X @ B @ gain + Q
    assert np.linalg.norm(residual) <= 1e-8 * np.linalg.norm(X)
    assert np.max(np.abs(np.linalg.eigvals(A - B @ gain))) < 1
    assert solution.relative_residual <= 1e-10


def test_solve_care_satisfies_the_equation():
    A = np.array([[0.0, 1.0], [2.0, -1.0]])
    B = np.array([[0.0], [1.0]])
    solution = adaptobs.solve_care(A, B, np.eye(2), np.eye(1))
    X = solution.X
    residual = A.T @ X + X @ A - X @ B @ B.T @ X + np.eye(2)
    assert np.linalg.norm(residual) <= 1e-10 * np.linalg.norm(X)
    assert np.max(np.linalg.eigvals(A - B @ B.T @ X).real) < 0


def test_the_satellite_kalman_gain_makes_a_minus_kc_schur():
    s = adaptobs.examples.satellite()
    kalman = adaptobs.steady_state_kalman_gain(s["A"], s["C"], np.eye(4) * 1e-4, np.eye(2) * 1e-2)
    A, C, P = s["A"], s["C"], kalman.P
    assert np.allclose(kalman.K, A @ P @ C.T @ np.linalg.inv(C @ P @ C.T + np.eye(2) * 1e-2), rtol=1e-10, atol=1e-14)
    assert np.max(np.abs(np.linalg.eigvals(A - kalman.K @ C))) < 1
    assert adaptobs.is_schur_stable(A - kalman.K @ C)
    assert not adaptobs.is_schur_stable(A)


def test_kalman_bucy_gain_makes_a_minus_kc_hurwitz():
    A = np.array([[0.0, 1.0], [-2.0, 0.5]])
    C = np.array([[1.0, 0.0]])
    gain = adaptobs.kalman_bucy_gain(A, C, np.eye(2), np.eye(1))
    assert np.allclose(gain.K, gain.P @ C.T, rtol=1e-12)
    assert adaptobs.is_hurwitz_stable(A - gain.K @ C)
    assert not adaptobs.is_hurwitz_stable(A)


def test_an_undetectable_pair_is_refused_in_the_filter_s_terms():
    A = np.diag([1.5, 0.5])
    C = np.array([[0.0, 1.0]])
    with pytest.raises(adaptobs.ConfigurationError, match="steady_state_kalman_gain: argument 'A, C' must be detectable"):
        adaptobs.steady_state_kalman_gain(A, C, np.eye(2), np.eye(1))


def test_pole_placement_places_the_requested_spectrum():
    s = adaptobs.examples.satellite()
    poles = np.array([0.5 + 0.1j, 0.5 - 0.1j, 0.3, 0.2])
    injection = adaptobs.place_output_injection(s["A"], s["C"], poles)
    placed = np.sort_complex(np.linalg.eigvals(s["A"] - injection.L @ s["C"]))
    assert np.max(np.abs(placed - np.sort_complex(poles))) < 1e-8
    A = np.array([[0.0, 1.0], [0.0, 0.0]])
    B = np.array([[0.0], [1.0]])
    feedback = adaptobs.place_state_feedback(A, B, [-1.0, -2.0])
    assert np.allclose(np.sort(np.linalg.eigvals(A - B @ feedback.K).real), [-2.0, -1.0], atol=1e-12)
    with pytest.raises(adaptobs.ConfigurationError, match="place_output_injection"):
        adaptobs.place_output_injection(np.diag([1.0, 2.0]), np.array([[1.0, 0.0]]), [0.1, 0.2])


def test_discretize_zoh_matches_the_series_of_the_exponential():
    s = adaptobs.examples.satellite()
    Ac = np.array([[0, 1, 0, 0], [3 * 3.49e-4**2, 0, 0, 2 * 3.49e-4], [0, 0, 0, 1], [0, -2 * 3.49e-4, 0, 0]])
    zoh = adaptobs.discretize_zoh(Ac, np.eye(4), 0.1)
    term, exponential, integral = np.eye(4), np.eye(4), np.eye(4) * 0.1
    for j in range(1, 20):
        term = term @ Ac * 0.1 / j
        exponential = exponential + term
        integral = integral + term * 0.1 / (j + 1)
    assert np.allclose(zoh.Ad, exponential, rtol=0, atol=1e-15)
    assert np.allclose(zoh.Bd, integral, rtol=0, atol=1e-15)
    assert np.array_equal(zoh.Ad, s["A"]) and np.array_equal(zoh.Bd, s["H"])
    with pytest.raises(adaptobs.ConfigurationError, match="discretize_zoh: argument 'ts' must be positive"):
        adaptobs.discretize_zoh(Ac, np.eye(4), -0.1)
