"""The Takagi-Sugeno observer of Srinivasarengan et al. (2018) on the waste water
plant of section 6: the polytopic model, the observer (65)/(21), its replay of the
C++ example, its copies and refusals, and the vertex LMIs of theorems 1-2."""

import gc
import pickle
import weakref

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import assert_update_follows_run, cxx_example_table

B_CONSTANT = 0.4  # b of Table 1


def premises(x, u, theta):
    """Premise variables (75): z1 = u, z2 = x1 / (x2 + b), as the C++ example computes them."""
    return np.array([u[0], x[0] / (x[1] + B_CONSTANT)])


@pytest.fixture(scope="module")
def wwtp():
    return adaptobs.examples.wwtp()


def make_model(system, lmi=False):
    prefix = "lmi_" if lmi else ""
    return adaptobs.TakagiSugenoModel(system[prefix + "vertices"], system["C"], premises,
                                      system[prefix + "premise_bounds"], system["parameter_bounds"])


def paper_gains(system, K_theta=None):
    return adaptobs.TakagiSugenoGains(system["L"], system["K"], K_theta)


def make_observer(system, K_theta=None):
    return adaptobs.TakagiSugenoObserver(make_model(system), paper_gains(system, K_theta), system["x0_estimate"],
                                         system["theta0_estimate"])


def quasi_lpv(z, theta, system):
    """A(z, theta) and B of the plant (72) (the file comment of examples/models/wwtp.hpp)."""
    a = system["a0"] + theta[0]
    ts, c, d = system["Ts"], system["c"], system["d"]
    A = np.array([[1 - ts * z[0], ts * a * z[1]], [0.0, 1 - ts * c * a * z[1] - ts * z[0]]])
    return A, np.array([[0.0], [ts * d]])


def test_the_vertices_are_the_printed_ones_and_the_weights_are_the_sector_memberships(wwtp):
    vertices = adaptobs.sector_vertices(lambda z, th: quasi_lpv(z, th, wwtp), wwtp["premise_bounds"],
                                        wwtp["parameter_bounds"])
    assert len(vertices) == 8
    for (A, B), (A_cxx, B_cxx) in zip(vertices, wwtp["vertices"]):
        assert np.max(np.abs(A - A_cxx)) <= 1e-15 and np.array_equal(B, B_cxx)
    # A_3 and A_8 as printed in section 6 (z1 lower, z2 upper, theta lower; all upper).
    assert np.max(np.abs(vertices[2][0] - [[1, 2.92], [0, -0.17]])) < 0.01
    assert np.max(np.abs(vertices[7][0] - [[0.6, 11.7], [0, -4.1]])) < 0.05

    model = make_model(wwtp)
    assert model.sizes == (2, 1, 1, 1) and model.vertex_count == 8 and model.premise_count == 2
    (zl, zu), (tl, tu) = wwtp["premise_bounds"], wwtp["parameter_bounds"]
    z, theta = np.array([0.1, 5.0]), np.array([0.06])
    h = model.weights(z, theta)
    mu = [np.array([(zu[j] - z[j]) / (zu[j] - zl[j]), (z[j] - zl[j]) / (zu[j] - zl[j])]) for j in range(2)]
    mt = np.array([(tu[0] - theta[0]) / (tu[0] - tl[0]), (theta[0] - tl[0]) / (tu[0] - tl[0])])
    expected = np.einsum("i,j,k->ijk", mu[0], mu[1], mt).reshape(8)  # z1 the most significant bit (eq. (10))
    assert np.max(np.abs(h - expected)) < 1e-15
    assert abs(h.sum() - 1) < 1e-15
    # Outside the sectors the weights are those of the nearest point of the box (11).
    assert np.array_equal(model.weights([-1.0, 100.0], [1.0]), model.weights([zl[0], zu[1]], [tu[0]]))
    assert model.weights([-1.0, 100.0], [1.0])[3] == 1.0  # z1 lower, z2 upper, theta upper: vertex 4
    assert np.array_equal(adaptobs.sector_weights(z, wwtp["premise_bounds"], theta, wwtp["parameter_bounds"]), h)
    # The blended step is the plant (72) inside the sectors (the model is affine in z and theta).
    x, u = np.array([3.0, 0.8]), np.array([0.2])
    a = wwtp["a0"] + 0.06
    growth = a * x[0] * x[1] / (x[1] + wwtp["b"])
    plant = [x[0] + growth - x[0] * u[0], x[1] - wwtp["c"] * growth + (wwtp["d"] - x[1]) * u[0]]
    assert np.max(np.abs(model.step(x, u, theta) - plant)) < 1e-14
    assert np.array_equal(model.premises(x, u, theta), premises(x, u, theta))


def test_the_observer_estimates_the_growth_rate_error_and_the_unmeasured_substrate(wwtp):
    data = adaptobs.examples.simulate_wwtp(500, theta=0.1)
    observer = make_observer(wwtp)
    result = observer.run(data["U"], data["Y"])
    assert np.all(result.status == UpdateStatus.accepted)
    # Row k is the estimate after sample k, i.e. of x_{k+1}; the 300-sample criterion of the C++ example.
    assert np.max(np.abs(result.parameters[300:, 0] - 0.1)) < 0.01
    assert np.max(np.abs(result.state[299:-1] - data["X"][300:])) < 1e-3
    assert abs(result.parameters[-1, 0] - 0.1) < 1e-3
    assert np.all(result.diagnostics["premises_in_sectors"] == 1.0)
    assert abs(observer.weights.sum() - 1) < 1e-15 and observer.premises_in_sectors
    assert np.array_equal(observer.premises, premises(result.state[-2], data["U"][-1], result.parameters[-2]))
    # From x_hat_0 = (6, 0), z2 = 6 / 0.4 = 15 lies beyond its sector's 14.63: clipped, and reported (Remark 8).
    outside = adaptobs.TakagiSugenoObserver(make_model(wwtp), paper_gains(wwtp), [6.0, 0.0], [0.0])
    first = outside.run(data["U"][:1], data["Y"][:1])
    assert first.diagnostics["premises_in_sectors"][0] == 0.0 and not outside.premises_in_sectors
    assert outside.premises[1] == 15.0
    # Vertex i = 4 j_z1 + 2 j_z2 + j_theta: z2 at its upper bound leaves the j_z2 = 0 vertices no weight;
    # z1 = u_0 = 0.225 in [0, 0.4] and theta_hat = 0 in [-0.3, 0.3] split the rest.
    assert np.array_equal(outside.weights[[0, 1, 4, 5]], np.zeros(4))
    assert abs(outside.weights[6] + outside.weights[7] - 0.225 / 0.4) < 1e-15
    assert abs(outside.weights[2] - 0.5 * (0.4 - 0.225) / 0.4) < 1e-15


def test_the_wwtp_replay_matches_the_cxx_example(tmp_path, wwtp):
    """The C++ example's CSV (same plant, same losses from the same seed) against the Python run, to 1e-12."""
    table = cxx_example_table(tmp_path, "wwtp", "--drop", "0.2", "--seed", "7",
                              unbuilt="the wwtp example is built only with DSDP (its LMI design)")
    data = adaptobs.examples.simulate_wwtp(len(table), theta=0.1, drop=0.2, seed=7)
    assert np.array_equal(data["Y"][:, 0], table["y_1"])
    assert np.array_equal(data["present"][:, 0], table["y_available"] == 1)
    assert 50 < np.count_nonzero(~data["present"]) < 150  # the losses were drawn
    observer = make_observer(wwtp)
    result = observer.run(data["U"], data["Y"], present=data["present"])
    assert np.all(result.status == UpdateStatus.accepted)
    # Row k of the CSV holds the estimates before sample k, the run's row k those after it.
    cxx_state = np.column_stack([table["xhat_1"], table["xhat_2"]])
    assert np.max(np.abs(result.state[:-1] - cxx_state[1:])) <= 1e-12
    assert np.max(np.abs(result.parameters[:-1, 0] - table["thetahat_1"][1:])) <= 1e-12
    # The weights of figure 5: row k's are those the update of sample k used.
    stepped = make_observer(wwtp)
    weights = []
    for k in range(len(table)):
        stepped.update(data["U"][k], data["Y"][k], present=data["present"][k])
        weights.append(stepped.weights)
    cxx_weights = np.column_stack([table[f"h_{i}"] for i in range(1, 9)])
    assert np.max(np.abs(np.array(weights) - cxx_weights)) <= 1e-12
    if adaptobs.has_lmi:
        # The example's own design (theorem 2, Remark 6, corollary 1 on the input sector [0.05, 0.4]).
        design = adaptobs.synthesize_takagi_sugeno_gains(
            make_model(wwtp, lmi=True), Q_x=wwtp["lmi_Q_x"], Q_theta=wwtp["lmi_Q_theta"],
            parameter_gain=wwtp["lmi_parameter_gain"])
        lmi_observer = adaptobs.TakagiSugenoObserver(make_model(wwtp, lmi=True), design.gains, wwtp["x0_estimate"],
                                                     wwtp["theta0_estimate"])
        lmi_result = lmi_observer.run(data["U"], data["Y"], present=data["present"])
        cxx_lmi = np.column_stack([table["xhat_lmi_1"], table["xhat_lmi_2"]])
        assert np.max(np.abs(lmi_result.state[:-1] - cxx_lmi[1:])) <= 1e-12
        assert np.max(np.abs(lmi_result.parameters[:-1, 0] - table["thetahat_lmi_1"][1:])) <= 1e-12


@pytest.mark.parametrize("K_theta", [None, [[1e-3]]])
def test_run_equals_update_and_copies_continue_bit_for_bit(wwtp, K_theta):
    data = adaptobs.examples.simulate_wwtp(400, theta=0.05)
    U, Y = data["U"], data["Y"].copy()
    present = np.ones(Y.shape, bool)
    present[100:130, 0] = False
    Y[100:130, 0] = np.nan  # absent: ignored
    Y[200, 0] = np.inf  # present: the sample is rejected
    result, batch, stepped = assert_update_follows_run(lambda: make_observer(wwtp, K_theta), U, Y, present,
                                                       {150: "pickle", 250: "deepcopy", 300: "copy"},
                                                       fields=("state", "parameters", "output_error"))
    assert result.status[200] == UpdateStatus.nonfinite_input
    assert np.count_nonzero(result.status) == 1
    assert stepped.step == batch.step == 399
    assert np.array_equal(stepped.weights, batch.weights)
    assert stepped.has_leakage == (K_theta is not None)
    # The gaps were time updates: the output error is zero there, and the estimate still converged.
    assert np.all(result.output_error[100:130] == 0) and np.all(result.output_error[90:100] != 0)
    assert abs(result.parameters[-1, 0] - 0.05) < (0.01 if K_theta is None else 0.05)


def test_a_pickled_model_and_observer_carry_their_premise_function(wwtp):
    model = pickle.loads(pickle.dumps(make_model(wwtp)))
    assert model.premise_function is premises
    assert np.array_equal(model.vertex_state_matrices, make_model(wwtp).vertex_state_matrices)
    observer = make_observer(wwtp)
    data = adaptobs.examples.simulate_wwtp(50)
    observer.run(data["U"], data["Y"])
    clone = pickle.loads(pickle.dumps(observer))
    assert clone.model.premise_function is premises
    assert [np.array_equal(a, b) for a, b in zip(clone.gains.L, wwtp["L"])] == [True] * 8
    gains = pickle.loads(pickle.dumps(paper_gains(wwtp, [[2e-3]])))
    assert gains.K_theta[0, 0] == 2e-3 and gains.K[7][0, 0] == 0.03 and np.array_equal(gains.L[4], wwtp["L"][4])
    # A lambda cannot be pickled: the model says so rather than losing it.
    unpicklable = adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], lambda x, u, th: premises(x, u, th),
                                             wwtp["premise_bounds"], wwtp["parameter_bounds"])
    with pytest.raises((pickle.PicklingError, AttributeError)):
        pickle.dumps(unpicklable)


def test_a_snapshot_restores_and_one_of_another_configuration_is_refused(wwtp):
    data = adaptobs.examples.simulate_wwtp(300)
    original = make_observer(wwtp)
    original.run(data["U"][:120], data["Y"][:120])
    state = original.snapshot()
    assert state["type"] == "TakagiSugenoObserver"
    assert np.array_equal(state["matrices"]["L[3]"], wwtp["L"][3].reshape(2, 1))
    other = adaptobs.TakagiSugenoObserver(make_model(wwtp), adaptobs.TakagiSugenoGains([np.zeros(2)] * 8, [0.0] * 8),
                                          [1.0, 1.0], [0.2])
    other.restore(state)
    a = original.run(data["U"][120:], data["Y"][120:])
    b = other.run(data["U"][120:], data["Y"][120:])
    assert np.array_equal(a.state, b.state) and np.array_equal(a.parameters, b.parameters)
    leaky = make_observer(wwtp, K_theta=[[1e-3]])
    before = leaky.snapshot()
    with pytest.raises(ConfigurationError, match="holds 'has_leakage' = 0 where this TakagiSugenoObserver has 1"):
        leaky.restore(state)
    state["matrices"]["K_y[5]"] = np.array([[np.nan]])
    with pytest.raises(ConfigurationError, match=r"restore: argument 'gains.K\[5\]' must contain only finite numbers"):
        other.restore(state)
    after = leaky.snapshot()
    for name, value in before["matrices"].items():
        assert np.array_equal(value, after["matrices"][name])


def test_bad_constructor_arguments_name_the_argument(wwtp):
    V, C, zb, tb = wwtp["vertices"], wwtp["C"], wwtp["premise_bounds"], wwtp["parameter_bounds"]
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoModel: argument 'vertices' must hold 2\^\(nz \+ np\) "
                                                 r"vertices \(8, got 7\)"):
        adaptobs.TakagiSugenoModel(V[:7], C, premises, zb, tb)
    with pytest.raises(ConfigurationError, match=r"argument 'vertices' must hold 2\^\(nz \+ np\) vertices \(8, got 0\)"):
        adaptobs.TakagiSugenoModel([], C, premises, zb, tb)
    with pytest.raises(ConfigurationError, match=r"argument 'premise_bounds' must have lower < upper.*entry 1"):
        adaptobs.TakagiSugenoModel(V, C, premises, (zb[0], [0.4, 0.0]), tb)
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoModel: argument 'premises' is required"):
        adaptobs.TakagiSugenoModel(V, C, None, zb, tb)
    with pytest.raises(TypeError, match=r"argument 'premises' must be a callable premises\(x, u, theta\) or None"):
        adaptobs.TakagiSugenoModel(V, C, "z", zb, tb)
    with pytest.raises(TypeError, match=r"argument 'vertices\[2\]' must be a pair \(A_i, B_i\)"):
        adaptobs.TakagiSugenoModel(V[:2] + [(V[2][0], V[2][1], None)] + V[3:], C, premises, zb, tb)
    model = make_model(wwtp)
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver: argument 'gains.L' must hold one matrix per "
                                                 r"vertex \(8, got 7\)"):
        adaptobs.TakagiSugenoObserver(model, adaptobs.TakagiSugenoGains(wwtp["L"][:7], wwtp["K"]), [3, 0.6], [0])
    L = [l.copy() for l in wwtp["L"]]
    L[2][1] = np.nan
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver: argument 'gains.L\[2\]' must contain only "
                                                 r"finite numbers"):
        adaptobs.TakagiSugenoObserver(model, adaptobs.TakagiSugenoGains(L, wwtp["K"]), [3, 0.6], [0])
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver: argument 'gains.K_theta' must be 1x1"):
        adaptobs.TakagiSugenoObserver(model, paper_gains(wwtp, np.eye(2)), [3, 0.6], [0])
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver: argument 'x0'"):
        adaptobs.TakagiSugenoObserver(model, paper_gains(wwtp), [3, 0.6, 1], [0])
    with pytest.raises(TypeError, match=r"argument 'gains' must be an adaptobs.TakagiSugenoGains"):
        adaptobs.TakagiSugenoObserver(model, wwtp["L"], [3, 0.6], [0])


def test_wrong_shapes_name_the_argument_and_both_shapes_and_change_nothing(wwtp):
    observer = make_observer(wwtp)
    observer.update([0.2], [4.0])
    before = observer.snapshot()
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver.update: argument 'u' must be \(1,\) \(got \(2,\)\)"):
        observer.update([0.2, 0.1], [4.0])
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoObserver.run: argument 'Y' must be 5x1 \(samples x 1\) "
                                                 r"\(got 5x2\)"):
        observer.run(np.zeros((5, 1)), np.zeros((5, 2)))
    with pytest.raises(ConfigurationError, match=r"argument 'Psi' must be None"):
        observer.update([0.2], [4.0], np.zeros((2, 1)))
    bad = adaptobs.TakagiSugenoObserver(
        adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], lambda x, u, th: np.zeros(3), wwtp["premise_bounds"],
                                   wwtp["parameter_bounds"]), paper_gains(wwtp), [3, 0.6], [0])
    with pytest.raises(ConfigurationError, match=r"TakagiSugenoModel: argument 'premises\(x, u, theta\)' must be "
                                                 r"\(2,\) \(got \(3,\)\)"):
        bad.update([0.2], [4.0])
    assert bad.step == 0 and np.array_equal(bad.state, [3, 0.6])
    after = observer.snapshot()
    for name, value in before["matrices"].items():
        assert np.array_equal(value, after["matrices"][name])


def test_a_nan_sample_or_premise_is_rejected_and_leaves_the_state_bit_identical(wwtp):
    data = adaptobs.examples.simulate_wwtp(60)
    observer = make_observer(wwtp)
    observer.run(data["U"], data["Y"])
    before = observer.snapshot()
    assert observer.update([0.2], [np.nan]) == UpdateStatus.nonfinite_input
    assert observer.update([np.nan], [4.0]) == UpdateStatus.nonfinite_input
    after = observer.snapshot()
    assert before["integers"] == after["integers"]
    for name, value in before["matrices"].items():
        assert np.array_equal(value, after["matrices"][name]), name
    # A premise function that returns NaN (here: x2 = -b) rejects the sample too.
    observer.restore(before)
    nan_model = adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], lambda x, u, th: np.array([u[0], np.nan]),
                                           wwtp["premise_bounds"], wwtp["parameter_bounds"])
    rejecting = adaptobs.TakagiSugenoObserver(nan_model, paper_gains(wwtp), [3, 0.6], [0])
    assert rejecting.update([0.2], [4.0]) == UpdateStatus.nonfinite_input
    assert rejecting.step == 0 and np.array_equal(rejecting.weights, np.zeros(8))
    # A raising premise function raises through update and run, and changes nothing.
    def raising(x, u, th):
        raise RuntimeError("no premise")
    failing = adaptobs.TakagiSugenoObserver(
        adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], raising, wwtp["premise_bounds"],
                                   wwtp["parameter_bounds"]), paper_gains(wwtp), [3, 0.6], [0])
    with pytest.raises(RuntimeError, match="no premise"):
        failing.run(data["U"], data["Y"])
    assert failing.step == 0 and np.array_equal(failing.state, [3, 0.6])
    # One that raises at the sixth sample of a run: the first five leave no trace either.
    calls = []

    def raising_late(x, u, th):
        calls.append(1)
        if len(calls) > 5:
            raise RuntimeError("no premise")
        return np.array([u[0], x[1]])
    late = adaptobs.TakagiSugenoObserver(
        adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], raising_late, wwtp["premise_bounds"],
                                   wwtp["parameter_bounds"]), paper_gains(wwtp), [3, 0.6], [0])
    with pytest.raises(RuntimeError, match="no premise"):
        late.run(data["U"], data["Y"])
    assert len(calls) == 6 and late.step == 0 and np.array_equal(late.state, [3, 0.6])


def test_a_cycle_through_the_premise_function_is_collected(wwtp):
    class Holder:
        pass

    holder = Holder()

    def z(x, u, theta):
        holder.observer  # the closure keeps holder, and so the observer, alive
        return premises(x, u, theta)

    holder.observer = None
    model = adaptobs.TakagiSugenoModel(wwtp["vertices"], wwtp["C"], z, wwtp["premise_bounds"], wwtp["parameter_bounds"])
    holder.observer = adaptobs.TakagiSugenoObserver(model, paper_gains(wwtp), [3, 0.6], [0])
    holder.model = model  # z -> holder -> model -> z as well
    del model
    assert holder.observer.update([0.2], [4.0]) == UpdateStatus.accepted
    alive = weakref.ref(holder)
    del holder, z
    gc.collect()
    assert alive() is None


def lmi_data(system):
    return adaptobs.TakagiSugenoLmiData(
        [A for A, _ in system["lmi_vertices"]], [B for _, B in system["lmi_vertices"]], system["C"],
        system["lmi_Q_x"], system["lmi_Q_theta"])


def test_the_vertex_lmis_are_assembled_as_derived_and_checked_by_their_eigenvalues(wwtp):
    """M_i of theorem 2 (eq. (71)) at a candidate, block by block against the formulas, and the check's figures."""
    data = lmi_data(wwtp)
    assert data.vertex_lmi_size == 3 * 3 + 3 + 2 * 8 * 3 == 60
    rng = np.random.default_rng(3)
    P0 = np.array([[2.0, 0.3], [0.3, 1.0]])
    R = [rng.normal(size=(2, 1)) for _ in range(8)]
    F = [np.array([[0.03 * 4.0]])] * 8  # K_i = 0.03 with P1 = 4
    cert = adaptobs.TakagiSugenoCertificate(P0, [[4.0]], R, F, (0.1, 0.2, 0.3, 0.4), np.eye(2) * 5, [[6.0]])
    C = wwtp["C"]
    calA, calB = data.stacked_A, data.stacked_B
    for i in (0, 5):
        M = adaptobs.takagi_sugeno_vertex_lmi(data, cert, i)
        assert M.shape == (60, 60) and np.array_equal(M, M.T)
        A = data.A[i]
        P0i = A.T @ P0 - C.T @ R[i].T  # (41)
        # (1,3): Phi_i^T P = [[P0i, -C^T F_i^T], [0, Phi22^T P1]], Phi22 = 0 as printed (66).
        assert np.max(np.abs(M[0:2, 6:8] - P0i)) < 1e-15
        assert np.max(np.abs(M[0:2, 8:9] + C.T @ F[i].T)) < 1e-15
        assert M[2, 8] == 0.0
        # (1,1) Q_e - P; (2,2) -Gamma + r (lambda_1 + lambda_2) I; (3,3) -P.
        assert np.allclose(M[0:3, 0:3], np.diag([1e-3, 1e-3, 0.1]) - np.diag([0, 0, 4.0]) - np.pad(P0, (0, 1)),
                           rtol=0, atol=1e-15)
        assert np.allclose(M[3:6, 3:6], np.diag([-5 + 8 * 0.3, -5 + 8 * 0.3, -6 + 8 * 0.7]), rtol=0, atol=1e-14)
        # (1,5) T_1i = [P0i calA, P0i calB, 0, 0]; (4,5) T4 = [0, 0, P0 calA, P0 calB]; Lambda.
        assert np.max(np.abs(M[0:2, 12:28] - P0i @ calA)) < 1e-14
        assert np.max(np.abs(M[0:2, 28:36] - P0i @ calB)) < 1e-14
        assert np.max(np.abs(M[9:11, 36:52] - P0 @ calA)) < 1e-14
        assert np.max(np.abs(M[9:11, 52:60] - P0 @ calB)) < 1e-14
        assert np.array_equal(np.diag(M)[12:60], -np.repeat([0.1, 0.3, 0.2, 0.4], [16, 8, 16, 8]))
    check = adaptobs.check_takagi_sugeno_certificate(data, cert)
    largest = max(np.linalg.eigvalsh(adaptobs.takagi_sugeno_vertex_lmi(data, cert, i)).max() for i in range(8))
    assert abs(check.max_vertex_eigenvalue - largest) <= 1e-13 * abs(largest)
    assert check.max_vertex_eigenvalue > 0 and not check.holds  # (1,1) Q_e - P has Q_x - P0 ... not a certificate
    assert abs(check.min_eigenvalue_P0 - np.linalg.eigvalsh(P0).min()) < 1e-14
    assert check.min_eigenvalue_P1 == 4.0 and check.min_lambda == 0.1 and check.min_eigenvalue_Gamma == 5.0
    # A non-symmetric P0 proves nothing.
    skew = adaptobs.TakagiSugenoCertificate([[2.0, 0.3], [0.0, 1.0]], [[4.0]], R, F, (0.1, 0.2, 0.3, 0.4),
                                            np.eye(2), [[1.0]])
    assert adaptobs.check_takagi_sugeno_certificate(data, skew).min_eigenvalue_P0 == -np.inf
    # Theorem 1 (eq. (29)) adds the Theta and Delta Theta columns: exact reading Phi22 = I - K_theta, G = K_theta.
    t1 = adaptobs.TakagiSugenoLmiData(data.A, data.B, C, data.Q_x, data.Q_theta,
                                      theorem=adaptobs.TakagiSugenoTheorem.time_varying_parameters,
                                      error_model=adaptobs.ParameterErrorModel.exact, K_theta=[[0.01]])
    Phi22, G = adaptobs.parameter_error_blocks(t1)
    assert Phi22[0, 0] == 0.99 and G[0, 0] == 0.01
    assert t1.vertex_lmi_size == 62
    with pytest.raises(ConfigurationError, match=r"check_takagi_sugeno_certificate: argument 'certificate.Gamma_theta'"):
        adaptobs.check_takagi_sugeno_certificate(t1, cert)
    with pytest.raises(ConfigurationError, match=r"takagi_sugeno_vertex_lmi: argument 'i' must be a vertex index"):
        adaptobs.takagi_sugeno_vertex_lmi(data, cert, 8)


@pytest.mark.skipif(not adaptobs.has_lmi, reason="the module was built without DSDP")
def test_the_lmi_synthesis_certifies_the_plant_and_its_gains_stabilize_every_vertex(wwtp):
    model = make_model(wwtp, lmi=True)
    design = adaptobs.synthesize_takagi_sugeno_gains(model, Q_x=wwtp["lmi_Q_x"], Q_theta=wwtp["lmi_Q_theta"],
                                                     parameter_gain=wwtp["lmi_parameter_gain"])
    assert design.status == adaptobs.SynthesisStatus.feasible and design.feasible
    assert design.check.holds and design.check.max_vertex_eigenvalue < 0
    assert 100 < design.beta < 1e4  # corollary 1 on the input sector [0.05, 0.4]
    # The check is the independent one: recomputed from the certificate, the same figures.
    again = adaptobs.check_takagi_sugeno_certificate(lmi_data(wwtp), design.certificate)
    assert again.max_vertex_eigenvalue == design.check.max_vertex_eigenvalue
    # L_i = P0^-1 R_i, K_i = 0.03 imposed (31), and every A_i - L_i C is Schur (the (1,1)-(3,3) blocks).
    P0 = design.certificate.P0
    for i, (L, K) in enumerate(zip(design.gains.L, design.gains.K)):
        assert np.max(np.abs(L - np.linalg.solve(P0, design.certificate.R[i]))) < 1e-9
        assert abs(K[0, 0] - 0.03) < 1e-12
        assert np.max(np.abs(np.linalg.eigvals(model.A(i) - L @ wwtp["C"]))) < 1
    # The printed gains cannot be certified: A_i - L_i C is not Schur at four vertices.
    radii = [np.max(np.abs(np.linalg.eigvals(A - L @ wwtp["C"]))) for (A, _), L in zip(wwtp["vertices"], wwtp["L"])]
    assert sum(r >= 1 for r in radii) == 4
    # The paper's own sectors, by the largest margin with Gamma fixed (Remark 7).
    margin = adaptobs.synthesize_takagi_sugeno_gains(
        make_model(wwtp), Q_x=wwtp["lmi_Q_x"], Q_theta=wwtp["lmi_Q_theta"], parameter_gain=wwtp["lmi_parameter_gain"],
        objective=adaptobs.TakagiSugenoObjective.maximize_margin, fixed_gamma=1e8)
    assert margin.feasible and margin.margin > 0
    assert abs(margin.check.max_vertex_eigenvalue + margin.margin) < 1e-8  # M_i <= -t I, attained
    # Corollary 1 on those sectors (beta* about 4.6e7) is beyond DSDP: infeasible is its claim, returned without gains.
    beta = adaptobs.synthesize_takagi_sugeno_gains(make_model(wwtp), Q_x=wwtp["lmi_Q_x"], Q_theta=wwtp["lmi_Q_theta"],
                                                   parameter_gain=wwtp["lmi_parameter_gain"])
    assert beta.status == adaptobs.SynthesisStatus.infeasible and beta.gains is None
    assert beta.check.max_vertex_eigenvalue > 0 and not beta.check.holds
    # A point that fails the independent check is refused, with the library's message.
    with pytest.raises(ConfigurationError, match=r"synthesize_takagi_sugeno_gains: argument 'model' gives no verified "
                                                 r"solution \(not verified\): DSDP: .*maximum iterations.*largest "
                                                 r"eigenvalue of the vertex LMIs"):
        adaptobs.synthesize_takagi_sugeno_gains(model, Q_x=wwtp["lmi_Q_x"], Q_theta=wwtp["lmi_Q_theta"],
                                                parameter_gain=wwtp["lmi_parameter_gain"], max_iterations=2)
    with pytest.raises(ConfigurationError, match=r"argument 'options.fixed_gamma' must be set for the maximize_margin"):
        adaptobs.synthesize_takagi_sugeno_gains(model, objective=adaptobs.TakagiSugenoObjective.maximize_margin)


def test_has_lmi_says_whether_the_synthesis_is_there():
    assert isinstance(adaptobs.has_lmi, bool)
    assert hasattr(adaptobs, "synthesize_takagi_sugeno_gains") == adaptobs.has_lmi
