"""The checks from Python: proposition 2.2 of Guiro et al. (2008) on the paper's
example, the SPR tests on transfer functions worked by hand, the KYP
certificate and Ackermann's gain against NumPy, Floquet exponents and
transition matrices against closed forms, the detectors' distributions and
thresholds against their formulas, and the Monte-Carlo evaluator on the
satellite's thruster fault against a plain loop over the same seeds."""

import math
import threading

import numpy as np
import pytest

import adaptobs
from adaptobs import ConditionVerdict, ConfigurationError, UpdateStatus
from conftest import load_example, make_observer
from test_fault_detection import MONITOR_FROM, monitor_design, thruster_fault_data  # noqa: F401 (a fixture)


# ---- Guiro et al. (2008), proposition 2.2 ------------------------------------------------


@pytest.fixture(scope="module")
def guiro():
    system = adaptobs.examples.guiro()
    gains = adaptobs.design_guiro_gains(system["E"], system["C"], system["H0"], system["poles"])
    Psi = adaptobs.examples.simulate_guiro(200)["Psi"]  # Psi_k = E H_k, 200 x 2 x 1
    H = np.linalg.solve(system["E"], Psi)  # the interval regressors H_k
    assert np.array_equal(H[0], system["H0"])
    return system, gains, H


def test_around_h0_neither_condition_holds_although_the_observer_converges(guiro):
    system, gains, H = guiro
    report = adaptobs.check_guiro_convergence(system["E"], system["C"], gains.K, gains.Gamma, system["H0"], H)
    # ||W(k)||_2 = ||(I - K C) E (H_k - H0)||_2, written here in NumPy.
    ikc_e = (np.eye(2) - gains.K @ system["C"]) @ system["E"]
    w = np.array([np.linalg.norm(ikc_e @ (h - system["H0"]), 2) for h in H])
    assert np.allclose(report.w_norms, w, rtol=1e-13, atol=1e-15)
    # The C++ test's figures (tests/test_guiro_design.cpp): the paper prints 0.2156 = ||W(59)||.
    assert report.w_norms[1] == pytest.approx(0.06309072588204587, abs=1e-12)
    assert report.w_norms[10] == pytest.approx(0.17886340017982783, abs=1e-12)
    assert report.w_norms[59] == pytest.approx(0.2156, abs=5e-5)
    assert report.w_sum == pytest.approx(w.sum(), rel=1e-13)
    assert report.bound is not None
    assert report.bound.perturbation_margin == pytest.approx(0.0486, abs=5e-4)
    assert report.bound.perturbation_margin == pytest.approx((1 - report.bound.lambda_) / report.bound.M, rel=1e-15)
    assert report.condition_i == ConditionVerdict.fails and report.k0 is None
    assert report.condition_ii == ConditionVerdict.fails
    assert not report.certified
    assert "(i) fails" in report.summary()


def test_the_power_bound_is_the_smallest_m_for_its_lambda(guiro):
    system, gains, H = guiro
    # E = I, K = 0, Gamma = 0: U = I is not Schur, and proposition 2.1 does not apply.
    report = adaptobs.check_guiro_convergence(np.eye(2), system["C"], np.zeros((2, 1)), np.zeros((1, 1)),
                                              system["H0"], np.empty(0))
    assert report.bound is None and report.spectral_radius == pytest.approx(1.0, abs=1e-15)
    assert "not Schur" in report.summary() and not report.certified
    bound = adaptobs.check_guiro_convergence(system["E"], system["C"], gains.K, gains.Gamma, system["H0"], H).bound
    # sup_k ||U^k||_2 / lambda^k, over enough powers for U^k / lambda^k to have decayed.
    ratios, power = [], np.eye(3)
    for k in range(400):
        ratios.append(np.linalg.norm(power, 2) / bound.lambda_**k)
        power = power @ gains.U
    assert max(ratios) == pytest.approx(bound.M, rel=1e-10)
    assert max(abs(np.linalg.eigvals(gains.U))) < bound.lambda_ < 1


def test_around_the_limit_regressor_condition_i_holds_from_k0_11(guiro):
    system, gains, H = guiro
    report = adaptobs.check_guiro_convergence(system["E"], system["C"], gains.K, gains.Gamma, system["Hbar"], H)
    assert report.spectral_radius == pytest.approx(0.7464796255405619, abs=1e-10)
    assert report.condition_i == ConditionVerdict.holds and report.k0 == 11
    margin = report.bound.perturbation_margin
    assert report.w_norms[10] >= margin and np.all(report.w_norms[11:] < margin)
    assert report.tail_sup == report.w_norms[11:].max()
    assert report.rate == pytest.approx(report.bound.lambda_ + report.bound.M * report.tail_sup, rel=1e-15)
    assert report.rate < 1
    assert report.condition_ii == ConditionVerdict.undetermined  # W(k) ~ 1/(2k): the border of summability
    assert report.decay_exponent == pytest.approx(1.0, abs=0.1)
    assert report.certified


def test_a_vanishing_deviation_certifies_condition_ii(guiro):
    system, gains, _ = guiro
    constant = np.repeat(system["H0"][None], 40, axis=0)
    report = adaptobs.check_guiro_convergence(system["E"], system["C"], gains.K, gains.Gamma, system["H0"], constant)
    assert report.condition_ii == ConditionVerdict.holds and report.decay_exponent == math.inf
    assert report.k0 == 0 and report.certified


def test_guiro_check_refuses_bad_arguments_by_name(guiro):
    system, gains, H = guiro
    E, C = system["E"], system["C"]
    with pytest.raises(ConfigurationError,
                       match=r"check_guiro_convergence: argument 'H_sequence' must be an N x 2 x 1 array .* \(got 200x2\)"):
        adaptobs.check_guiro_convergence(E, C, gains.K, gains.Gamma, system["H0"], H[:, :, 0])
    with pytest.raises(ConfigurationError, match="check_guiro_convergence: argument 'Gamma' must be 1x1"):
        adaptobs.check_guiro_convergence(E, C, gains.K, np.eye(2), system["H0"], H)
    with pytest.raises(ConfigurationError, match="check_guiro_convergence: argument 'H_sequence'"):
        adaptobs.check_guiro_convergence(E, C, gains.K, gains.Gamma, system["H0"], np.full((3, 2, 1), np.nan))


# ---- Strict positive realness --------------------------------------------------------------
#
# G = (s + c)/((s + a)(s + b)) has Re G(jw) |D(jw)|^2 = q(w^2) with q(w) = (a + b - c) w + a b c,
# worked by hand: SPR iff c > 0 and c < a + b (the strict inequality is the condition at infinity).

# A controllable realization of (s + c)/(s^2 + d1 s + d0): A companion, b = e2, c = (c, 1).
def realization(c, d1, d0):
    return np.array([[0.0, 1.0], [-d0, -d1]]), np.array([0.0, 1.0]), np.array([c, 1.0])


def test_the_exact_test_on_transfer_functions_worked_by_hand():
    spr = adaptobs.strictly_positive_real([1, 2], [1, 4, 3])  # (s + 2)/((s + 1)(s + 3)): q = 2w + 6
    assert spr and spr.strictly_positive_real and spr.denominator_hurwitz
    assert spr.relative_degree == 1 and spr.high_frequency_gain == 1.0
    assert np.allclose(spr.q, [2.0, 6.0], rtol=0, atol=1e-14)
    assert spr.q_positive_on_nonnegative_axis and spr.strict_at_infinity
    border = adaptobs.strictly_positive_real([1, 3], [1, 3, 2])  # (s + 3)/((s + 1)(s + 2)): q = 6, a + b = c
    assert not border and border.q_positive_on_nonnegative_axis and not border.strict_at_infinity
    assert np.allclose(border.q, [6.0], rtol=0, atol=1e-14)  # Re G = 6/|D|^2 decays like w^-4
    zero = adaptobs.strictly_positive_real([1, -1], [1, 3, 2])  # (s - 1)/((s + 1)(s + 2)): q = 4w - 2
    assert not zero and zero.denominator_hurwitz and not zero.q_positive_on_nonnegative_axis
    assert np.allclose(zero.q, [4.0, -2.0], rtol=0, atol=1e-14)
    assert not adaptobs.strictly_positive_real([1, 1], [1, 1, -2]).denominator_hurwitz  # (s - 1)(s + 2)
    assert adaptobs.strictly_positive_real([1], [1, 3, 2]).relative_degree == 2
    assert adaptobs.strictly_positive_real([-1, -2], [1, 4, 3]).high_frequency_gain == -1.0
    assert adaptobs.strictly_positive_real([2.0], [1.0, 1.0])  # 2/(s + 1)
    conditions = adaptobs.spr_conditions([1, -1], [1, 3, 2])
    assert type(conditions) is adaptobs.SprConditions and not conditions
    assert not conditions.q_positive_on_nonnegative_axis and conditions.strict_at_infinity


def test_the_state_space_test_is_the_transfer_function_s():
    for (c, d1, d0), expected in [((2, 4, 3), True), ((3, 3, 2), False), ((-1, 3, 2), False)]:
        A, b, row = realization(c, d1, d0)
        spr = adaptobs.strictly_positive_real(A, b, row)
        assert bool(spr) is expected
        assert np.allclose(spr.q, adaptobs.strictly_positive_real([1, c], [1, d1, d0]).q, rtol=0, atol=1e-13)
        assert bool(adaptobs.strictly_positive_real(A, b.reshape(2, 1), row.reshape(1, 2))) is expected


def test_the_frequency_sweep_reports_its_margins():
    # (1 + w^2) Re G(jw) = (2 w^2 + 6)/(w^2 + 9) for (s + 2)/((s + 1)(s + 3)): least at w = 0, 2/3.
    sweep = adaptobs.spr_frequency_sweep(*realization(2, 4, 3))
    assert sweep and sweep.hurwitz
    assert sweep.min_weighted_real_part == pytest.approx(2 / 3, rel=1e-12) and sweep.at_frequency == 0.0
    assert sweep.high_frequency_limit == pytest.approx(2.0, rel=1e-14)  # -c A b = a + b - c
    # (s + 3)/((s + 1)(s + 2)): 6/(w^2 + 4), least at omega_max, and -c A b = 0.
    border = adaptobs.spr_frequency_sweep(*realization(3, 3, 2), omega_max=1e3, points=101)
    assert not border and border.at_frequency == pytest.approx(1e3, rel=1e-12)
    assert border.min_weighted_real_part == pytest.approx(6 / (1e6 + 4), rel=1e-9)
    assert border.high_frequency_limit == pytest.approx(0.0, abs=1e-14)
    # (s - 1)/((s + 1)(s + 2)): (4 w^2 - 2)/(w^2 + 4), -1/2 at w = 0.
    negative = adaptobs.spr_frequency_sweep(*realization(-1, 3, 2))
    assert not negative and negative.min_weighted_real_part == pytest.approx(-0.5, rel=1e-12)
    with pytest.raises(ConfigurationError, match="spr_frequency_sweep: argument 'omega_min, omega_max, points'"):
        adaptobs.spr_frequency_sweep(*realization(2, 4, 3), omega_min=10.0, omega_max=1.0)


def test_the_kyp_certificate_satisfies_the_lemma_in_numpy():
    A, b, c = realization(2, 4, 3)
    k = adaptobs.kyp_certificate(A, b, c)
    P = k.P
    assert np.array_equal(P, P.T)
    lyapunov = A.T @ P + P @ A
    assert np.max(np.abs(P @ b - c)) == pytest.approx(k.equality_residual, abs=1e-15) and k.equality_residual < 1e-12
    assert k.min_eigenvalue_P == pytest.approx(np.linalg.eigvalsh(P)[0], rel=1e-12) and k.min_eigenvalue_P > 0
    assert k.max_eigenvalue_lyapunov == pytest.approx(np.linalg.eigvalsh(lyapunov)[-1], rel=1e-10)
    assert k.max_eigenvalue_lyapunov < 0
    assert adaptobs.kyp_certificate(*realization(3, 3, 2)) is None  # not SPR: no certificate
    assert adaptobs.kyp_certificate(*realization(-1, 3, 2)) is None
    # P = I: P b - c = (-2, 0); A^T + A = [[0, -2], [-2, -8]] has eigenvalues -4 +- 2 sqrt 5.
    r = adaptobs.kyp_residuals(np.eye(2), A, b, c)
    assert r.equality_residual == 2.0 and r.min_eigenvalue_P == pytest.approx(1.0, rel=1e-15)
    assert r.max_eigenvalue_lyapunov == pytest.approx(-4 + 2 * math.sqrt(5), rel=1e-13)
    with pytest.raises(ConfigurationError, match=r"kyp_residuals: argument 'P' must be 2x2 \(got 3x3\)"):
        adaptobs.kyp_residuals(np.eye(3), A, b, c)
    with pytest.raises(ConfigurationError, match=r"kyp_certificate: argument 'b' must be 2x1 \(got 3x1\)"):
        adaptobs.kyp_certificate(A, [0.0, 1.0, 0.0], c)


def test_ackermann_places_the_characteristic_polynomial():
    # A - k c = [[-k1, 1], [-3 - k2, -4]] for c = (1, 0): det = s^2 + (k1 + 4) s + 4 k1 + 3 + k2.
    A = np.array([[0.0, 1.0], [-3.0, -4.0]])
    k = adaptobs.ackermann_observer_gain(A, [1.0, 0.0], [1.0, 5.0, 6.0])
    assert np.allclose(k, [1.0, -1.0], rtol=0, atol=1e-13)
    rng = np.random.default_rng(4)
    A3, c3 = rng.standard_normal((3, 3)), rng.standard_normal(3)
    p = np.poly([-1.0, -2.0, -3.0])
    k3 = adaptobs.ackermann_observer_gain(A3, c3, p)
    assert np.allclose(np.poly(A3 - np.outer(k3, c3)), p, rtol=0, atol=1e-9)
    with pytest.raises(ConfigurationError, match="ackermann_observer_gain: argument 'A, c' must be an observable pair"):
        adaptobs.ackermann_observer_gain(np.diag([-1.0, -2.0]), [1.0, 0.0], [1.0, 3.0, 2.0])
    with pytest.raises(ConfigurationError, match="ackermann_observer_gain: argument 'p' must be monic of degree n"):
        adaptobs.ackermann_observer_gain(A, [1.0, 0.0], [2.0, 5.0, 6.0])


def test_spr_arguments_are_named():
    with pytest.raises(ConfigurationError, match="strictly_positive_real: argument 'denominator' must be monic"):
        adaptobs.strictly_positive_real([1.0], [2.0, 1.0])
    with pytest.raises(ConfigurationError, match="spr_conditions: argument 'numerator' must have degree below"):
        adaptobs.spr_conditions([1.0, 1.0, 1.0], [1.0, 1.0])
    with pytest.raises(ConfigurationError, match=r"strictly_positive_real: argument 'c' must be 1x2 \(got 1x3\)"):
        adaptobs.strictly_positive_real(np.eye(2), [1.0, 0.0], [1.0, 0.0, 0.0])
    with pytest.raises(TypeError, match="strictly_positive_real: argument 'numerator' must be an array of real"):
        adaptobs.strictly_positive_real(["a"], [1.0, 1.0])


# ---- Periodic and time-varying systems -----------------------------------------------------


def expm_by_diagonalization(M):
    values, vectors = np.linalg.eig(M)
    return (vectors @ np.diag(np.exp(values)) @ np.linalg.inv(vectors)).real


def markus_yamabe(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[-1 + 1.5 * c * c, 1 - 1.5 * s * c], [-1 - 1.5 * s * c, -1 + 1.5 * s * s]])


def test_the_transition_matrix_of_a_constant_a_is_its_exponential():
    A = np.array([[-1.0, 2.0], [0.0, -3.0]])
    phi = adaptobs.transition_matrix(lambda t: A, 0.5, 2.0)
    assert np.allclose(phi, expm_by_diagonalization(A * 1.5), rtol=0, atol=1e-12)
    assert np.allclose(adaptobs.transition_matrix(A, 0.5, 2.0), phi, rtol=0, atol=0)  # a constant array
    # A(t) = cos(t) M commutes with itself: Phi(t1, t0) = exp(M (sin t1 - sin t0)).
    phi_t = adaptobs.transition_matrix(lambda t: math.cos(t) * A, 0.3, 2.5)
    assert np.allclose(phi_t, expm_by_diagonalization(A * (math.sin(2.5) - math.sin(0.3))), rtol=0, atol=1e-11)
    assert np.allclose(adaptobs.transition_matrix(A, 2.0, 0.5), np.linalg.inv(phi), rtol=1e-10, atol=0)


def test_floquet_exponents_of_a_constant_a_are_the_real_parts_of_its_eigenvalues():
    # Monodromy exp(A T): log|mu| / T = Re(lambda).
    rotation = np.array([[-0.5, 2.0], [-2.0, -0.5]])
    assert np.allclose(adaptobs.floquet_exponents(lambda t: rotation, 1.3), [-0.5, -0.5], rtol=0, atol=1e-6)
    A = np.array([[-1.0, 2.0], [0.0, -3.0]])
    exponents = adaptobs.floquet_exponents(A, 2.0)
    assert np.allclose(exponents, np.sort(np.linalg.eigvals(A).real)[::-1], rtol=0, atol=1e-6)
    assert adaptobs.is_exponentially_stable_periodic(A, 2.0)
    assert adaptobs.is_exponentially_stable_periodic(A, 2.0, margin=0.9)
    assert not adaptobs.is_exponentially_stable_periodic(A, 2.0, margin=1.1)


def test_markus_yamabe_is_unstable_although_frozen_time_stable():
    assert np.all(np.linalg.eigvals(markus_yamabe(0.3)).real == pytest.approx(-0.25, abs=1e-12))
    exponents = adaptobs.floquet_exponents(markus_yamabe, math.pi)
    # The solution e^{t/2} (-cos t, sin t) gives +1/2; Liouville: their sum is the mean trace, -1/2.
    assert exponents[0] == pytest.approx(0.5, abs=1e-6)
    assert exponents.sum() == pytest.approx(-0.5, abs=1e-6)
    assert not adaptobs.is_exponentially_stable_periodic(markus_yamabe, math.pi)


def test_a_dynamics_callable_that_raises_or_changes_shape_is_reported():
    class Broken(Exception):
        pass

    def raising(t):
        if t > 0.5:
            raise Broken("A(t) failed at t = %g" % t)
        return -np.eye(2)

    for check in (lambda: adaptobs.transition_matrix(raising, 0.0, 1.0),
                  lambda: adaptobs.floquet_exponents(raising, 1.0),
                  lambda: adaptobs.is_exponentially_stable_periodic(raising, 1.0)):
        with pytest.raises(Broken, match="A\\(t\\) failed"):
            check()
    resized = lambda t: -np.eye(2) if t < 0.5 else -np.eye(3)  # noqa: E731
    with pytest.raises(ConfigurationError, match=r"transition_matrix: argument 'A' must return an array of its "
                                                 r"first value's shape 2x2 at every t \(got 3x3 at t = 0\.5"):
        adaptobs.transition_matrix(resized, 0.0, 1.0, steps=4)
    with pytest.raises(ConfigurationError, match=r"floquet_exponents: argument 'A' must return a square matrix, an "
                                                 r"n x n array \(got \(2,\) at t = 0\)"):
        adaptobs.floquet_exponents(lambda t: np.ones(2), 1.0)
    with pytest.raises(ConfigurationError, match="is_exponentially_stable_periodic: argument 'A' must contain only"):
        adaptobs.is_exponentially_stable_periodic(lambda t: np.full((1, 1), np.nan if t > 0.5 else -1.0), 1.0)
    with pytest.raises(ConfigurationError, match="floquet_exponents: argument 'period' must be positive"):
        adaptobs.floquet_exponents(-np.eye(2), -1.0)
    with pytest.raises(ConfigurationError, match="transition_matrix: argument 'A' must be square"):
        adaptobs.transition_matrix(np.ones((2, 3)), 0.0, 1.0)


# ---- Distributions and thresholds of the detectors --------------------------------------------


def test_the_chi_square_tail_and_quantile_match_closed_forms():
    for x in (0.1, 1.0, 3.0, 10.0, 40.0):
        assert adaptobs.chi_square_upper_tail(2, x) == pytest.approx(math.exp(-x / 2), rel=1e-13)
        assert adaptobs.chi_square_upper_tail(1, x) == pytest.approx(math.erfc(math.sqrt(x / 2)), rel=1e-12)
        assert adaptobs.chi_square_upper_tail(4, x) == pytest.approx(math.exp(-x / 2) * (1 + x / 2), rel=1e-13)
    assert adaptobs.chi_square_upper_tail(3, -1.0) == 1.0
    for p in (0.5, 1e-3, 1e-12):
        assert adaptobs.chi_square_upper_quantile(2, p) == pytest.approx(-2 * math.log(p), rel=1e-12)
    assert adaptobs.chi_square_upper_quantile(1, 0.05) == pytest.approx(3.841458820694124, rel=1e-11)
    with pytest.raises(ConfigurationError, match="chi_square_upper_quantile: argument 'p' must lie in \\(0, 1\\)"):
        adaptobs.chi_square_upper_quantile(2, 1.5)
    with pytest.raises(ConfigurationError, match="chi_square_upper_tail: argument 'degrees_of_freedom'"):
        adaptobs.chi_square_upper_tail(adaptobs.chi_square_max_degrees_of_freedom * 10, 1.0)


def siegmund(drift, h, mean=0.0):
    delta, b = mean - drift, h + 1.166
    return b * b if delta == 0 else (math.exp(-2 * delta * b) + 2 * delta * b - 1) / (2 * delta * delta)


def test_the_cusum_run_length_is_siegmund_s_and_the_threshold_inverts_it():
    assert adaptobs.siegmund_overshoot == 1.166
    for drift, h, mean in [(0.5, 4.0, 0.0), (1.0, 6.0, 0.0), (0.5, 4.0, 2.0), (0.25, 3.0, 0.25)]:
        assert adaptobs.cusum_mean_run_length(drift, h, mean) == pytest.approx(siegmund(drift, h, mean), rel=1e-12)
    h = adaptobs.cusum_threshold(0.5, 1000.0, components=2)
    assert siegmund(0.5, h) == pytest.approx(2 * 2 * 1000.0, rel=1e-9)  # 4 sums racing
    assert adaptobs.cusum_threshold(0.5, 1000.0) < h
    with pytest.raises(ConfigurationError, match="cusum_threshold: argument 'drift' must be positive"):
        adaptobs.cusum_threshold(-1.0, 1000.0)
    with pytest.raises(ConfigurationError, match="cusum_threshold: argument 'mean_evaluations' is shorter"):
        adaptobs.cusum_threshold(0.5, 1.0)


def test_the_glr_threshold_gives_its_false_alarm_rate_on_fresh_normal_values():
    h = adaptobs.glr_threshold(10, 200.0)
    assert adaptobs.glr_threshold(10, 2000.0) > h
    glr = adaptobs.GlrDetector([0.0], [1.0], 10, h)
    for z in np.random.default_rng(12).standard_normal(40000):
        glr.update([z])
    assert 140 <= glr.alarm_count <= 260  # 200 expected; the design's own Monte-Carlo error is about 14 %
    with pytest.raises(ConfigurationError, match="glr_threshold: argument 'mean_evaluations' must lie in"):
        adaptobs.glr_threshold(10, 1.0)
    with pytest.raises(ConfigurationError, match="glr_threshold: argument 'window'"):
        adaptobs.glr_threshold(adaptobs.glr_max_window, 1e5)
    # The budget counts every simulated value and every draw: 20000 evaluations of 10000 components, drawn
    # anew for each candidate, once passed as "work 2e4" and simulated for half a minute.
    assert adaptobs.glr_simulation_work(1, 2.0, 10000) == 20000 * 10000 * 21 > adaptobs.glr_max_simulation_work
    with pytest.raises(ConfigurationError, match="glr_threshold: argument 'components' must be at most 1190 here"):
        adaptobs.glr_threshold(1, 2.0, 10000)


def test_the_sample_covariance_is_the_mean_outer_product():
    rng = np.random.default_rng(2)
    runs = [rng.standard_normal((50, 3)), rng.standard_normal((7, 3)) * 2]
    stacked = np.vstack(runs)
    assert np.allclose(adaptobs.sample_covariance(runs), stacked.T @ stacked / len(stacked), rtol=1e-14, atol=0)
    with pytest.raises(ConfigurationError, match="sample_covariance: argument 'runs' must hold at least two"):
        adaptobs.sample_covariance([np.ones((1, 2))])
    with pytest.raises(ConfigurationError, match=r"sample_covariance: argument 'runs\[1\]' must be an N x n array"):
        adaptobs.sample_covariance([np.ones((3, 2)), np.ones(3)])


# ---- Monte-Carlo evaluation of a detector ------------------------------------------------------

STEPS, FAULT_AT, FAULT_SIZE = 3000, 1555, -0.01  # 300 s; theta_2 loses 1 % of its efficiency at 155.5 s


def thruster_scenario(system, design):
    """scenario(seed, faulty): the satellite (the fault example's outputs, noise 0.01 from `seed`), the
    Guyader-Zhang observer and a FaultMonitor; the CUSUM's alarms after convergence, and what they name."""
    faulty_outputs = load_example("satellite_fault").faulty_outputs
    clean = adaptobs.examples.simulate_satellite(STEPS, noise=0.0)  # U and Psi
    ts = system["Ts"]

    def scenario(seed, faulty):
        Y = faulty_outputs(system, clean, FAULT_AT if faulty else STEPS, FAULT_SIZE, seed)
        result = make_observer(system).run(clean["U"], Y, clean["Psi"])
        status = result.status.copy()
        status[:MONITOR_FROM] = UpdateStatus.nonfinite_input
        alarms = adaptobs.FaultMonitor(design).run(result.parameters, result.output_error, status=status)
        raised = np.flatnonzero(alarms["cusum_alarm"])
        return adaptobs.MonitoredRun(MONITOR_FROM * ts, (STEPS - 1) * ts, raised * ts,
                                     alarms["cusum_isolated"][raised].astype(int))

    return scenario


@pytest.fixture(scope="module")
def sensitive_design(monitor_design):
    """The fault example's design with a CUSUM threshold for a false alarm every 30 evaluations
    (300 s at the stride of 10 s) instead of every hour: a 1 % fault is then caught, and the
    fault-free twins raise some false alarms."""
    system, design, _ = monitor_design
    state = design.__getstate__()
    state["threshold"] = adaptobs.cusum_threshold(state["drift"], 30.0, components=2)
    sensitive = adaptobs.FaultMonitorDesign.__new__(adaptobs.FaultMonitorDesign)
    sensitive.__setstate__(state)
    return system, sensitive


def test_the_evaluator_scores_the_thruster_fault_as_a_plain_loop_does(sensitive_design):
    system, design = sensitive_design
    scenario = thruster_scenario(system, design)
    seeds, first = 12, 40
    fault = adaptobs.FaultDescription(FAULT_AT * system["Ts"], parameter=1)
    summary = adaptobs.evaluate_detection(scenario, fault, seeds, first_seed=first, threads=2)
    # The same scoring by hand: the first alarm strictly after the fault, over the same seeds.
    delays, isolated, quiet, false_alarms, monitored = [], 0, 0, 0, 0.0
    faulty_runs, twins = [], []
    for seed in range(first, first + seeds):
        run, twin = scenario(seed, True), scenario(seed, False)
        faulty_runs.append(run)
        twins.append(twin)
        after = [a for a in sorted(run.alarms, key=lambda a: a.time) if a.time > fault.time]
        quiet += all(a.time > fault.time for a in run.alarms)
        if after:
            delays.append(after[0].time - fault.time)
            isolated += after[0].isolated == fault.parameter
        false_alarms += len(twin.alarms)
        monitored += twin.end - twin.start
    assert summary.seeds == seeds
    assert summary.detection_rate == len(delays) / seeds
    assert summary.mean_detection_delay == sum(sorted(delays)) / len(delays)
    assert summary.isolation_rate == isolated / len(delays)
    assert summary.quiet_before_fault_rate == quiet / seeds
    assert summary.false_alarms == false_alarms
    assert summary.fault_free_time == monitored
    assert summary.false_alarm_rate == false_alarms / monitored
    assert np.array_equal(summary.delays, delays)
    assert summary.p95_detection_delay == sorted(delays)[math.ceil(0.95 * len(delays)) - 1]
    # A 1 % fault: caught in most runs, some tens of seconds later, mostly isolated to theta_2, with
    # false alarms in the twins and before the fault (the figures of these seeds).
    assert 0.5 <= summary.detection_rate <= 1 and 5.0 < summary.mean_detection_delay < 100.0
    assert len(set(delays)) > 1 and 0.5 <= summary.isolation_rate < 1
    assert 0 < summary.false_alarms and summary.quiet_before_fault_rate < 1
    # Recorded runs give the same summary; so does any number of threads.
    recorded = adaptobs.evaluate_detection((faulty_runs, twins), fault, first_seed=first)
    single = adaptobs.evaluate_detection(scenario, fault, seeds, first_seed=first, threads=1)
    for other in (recorded, single):
        for name in ("detection_rate", "mean_detection_delay", "p95_detection_delay", "isolation_rate",
                     "quiet_before_fault_rate", "false_alarms", "fault_free_time", "false_alarm_rate"):
            assert getattr(other, name) == getattr(summary, name), name
        assert np.array_equal(other.delays, summary.delays)


def test_an_exception_of_the_scenario_reaches_the_caller_as_it_is():
    class ScenarioFailed(Exception):
        pass

    def scenario(seed, faulty):
        if seed == 3:
            raise ScenarioFailed(f"seed {seed}")
        return (0.0, 10.0, [5.0])

    for threads in (1, 2, 0):
        with pytest.raises(ScenarioFailed, match="seed 3"):
            adaptobs.evaluate_detection(scenario, 1.0, 8, threads=threads)
    summary = adaptobs.evaluate_detection(lambda seed, faulty: (0.0, 10.0, [5.0, 2.0 + seed]), 1.0, 3, threads=2)
    assert summary.detection_rate == 1.0 and summary.mean_detection_delay == 2.0  # delays 1, 2, 3
    assert summary.false_alarms == 6 and summary.fault_free_time == 30.0 and summary.false_alarm_rate == 0.2


def test_two_threads_run_two_scenarios_at_once():
    """The first faulty runs of both threads meet at a barrier: with the GIL held between calls, or
    the calls serialized, the barrier would break (after its timeout) instead of opening."""
    barrier = threading.Barrier(2, timeout=60)

    def scenario(seed, faulty):
        if faulty:
            barrier.wait()  # releases the GIL while it waits
        return adaptobs.MonitoredRun(0.0, 1.0, [0.5 + 0.1 * seed], [seed])

    summary = adaptobs.evaluate_detection(scenario, adaptobs.FaultDescription(0.2, parameter=1), 2, threads=2)
    assert summary.detection_rate == 1.0 and summary.isolation_rate == 0.5
    assert np.allclose(summary.delays, [0.3, 0.4], rtol=0, atol=1e-15) and summary.false_alarms == 2


def test_the_evaluator_refuses_bad_runs_and_arguments_by_name():
    with pytest.raises(TypeError, match=r"evaluate_detection: argument 'scenario\(seed, faulty\)' must be an "
                                        r"adaptobs.MonitoredRun or a tuple"):
        adaptobs.evaluate_detection(lambda seed, faulty: [0.0, 1.0], 0.5, 2, threads=2)
    with pytest.raises(ConfigurationError, match="evaluate_detection: argument 'scenario' must return runs with"):
        adaptobs.evaluate_detection(lambda seed, faulty: (0.0, 1.0, [2.0]), 0.5, 2)
    with pytest.raises(ConfigurationError, match="evaluate_detection: argument 'seeds' must be at least 1"):
        adaptobs.evaluate_detection(lambda seed, faulty: (0.0, 1.0, []), 0.5, 0)
    with pytest.raises(ConfigurationError, match="evaluate_detection: argument 'seeds' is required"):
        adaptobs.evaluate_detection(lambda seed, faulty: (0.0, 1.0, []), 0.5)
    with pytest.raises(ConfigurationError, match=r"evaluate_detection: argument 'scenario\[1\]' must hold one"):
        adaptobs.evaluate_detection(([(0.0, 1.0, [])], []), 0.5)
    with pytest.raises(ConfigurationError, match=r"MonitoredRun: argument 'isolated' must be \(2,\)"):
        adaptobs.MonitoredRun(0.0, 1.0, [0.5, 0.6], [1])
    with pytest.raises(TypeError, match="evaluate_detection: argument 'fault' must be an adaptobs.FaultDescription"):
        adaptobs.evaluate_detection(lambda seed, faulty: (0.0, 1.0, []), "soon", 1)
