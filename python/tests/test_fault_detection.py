"""Fault detection from Python: the detectors against their recursions
written here in NumPy, a FaultMonitor designed from fault-free satellite runs
that catches and isolates a thruster fault, batch against step, state that
survives pickling, and refusals that name the argument."""

import copy
import pickle

import numpy as np
import pytest

import adaptobs
from adaptobs import ConfigurationError, UpdateStatus
from conftest import load_example, make_observer

satellite_fault = load_example("satellite_fault")
MONITOR_FROM = satellite_fault.MONITOR_FROM  # samples: the estimates have converged (100 s)


def thruster_fault_data(system, steps, fault_at, seed):
    """The satellite with theta_2 dropping by 40 % at sample `fault_at`, output noise 0.01."""
    clean = adaptobs.examples.simulate_satellite(steps, noise=0.0)
    rng = np.random.default_rng(seed)
    x = system["x0"].copy()
    Y = np.empty((steps, 2))
    for k in range(steps):
        theta = np.array([1.0, 1.5 * (0.6 if k >= fault_at else 1.0)])
        Y[k] = system["C"] @ x + 0.01 * rng.standard_normal(2)
        x = system["A"] @ x + clean["Psi"][k] @ theta
    return clean["U"], Y, clean["Psi"]


@pytest.fixture(scope="module")
def monitor_design():
    """The fault example's design: twenty fault-free runs of 3100 s, false alarms every hour (36000 samples)
    per test."""
    system = adaptobs.examples.satellite()
    design, parameters = satellite_fault.fault_free_design(system)
    return system, design, parameters


def test_the_design_is_the_calibration_of_its_record(monitor_design):
    system, design, parameters = monitor_design
    calibration = adaptobs.calibrate_cusum(parameters, system["theta"], 1.0, 360.0, 100)
    assert calibration.threshold == design.cusum.threshold
    assert np.array_equal(calibration.scale, design.cusum.scale)
    assert design.stride == 100 and design.window == 100
    assert 25 <= design.glr_checked_alarms <= 100
    assert design.false_alarm_probability == pytest.approx(100 / 36000, rel=1e-15)
    assert design.chi_square_windows == 20 * 300


def test_a_thruster_fault_is_detected_and_isolated(monitor_design):
    system, design, _ = monitor_design
    U, Y, Psi = thruster_fault_data(system, 4500, fault_at=1500, seed=5)
    result = make_observer(system).run(U, Y, Psi)
    status = result.status.copy()
    status[:MONITOR_FROM] = UpdateStatus.nonfinite_input  # not yet converged: not monitored
    alarms = adaptobs.FaultMonitor(design).run(result.parameters, result.output_error, status=status)
    for test in ("cusum_alarm", "glr_alarm"):
        first = np.flatnonzero(alarms[test])
        assert first.size > 0 and 1500 <= first[0] <= 1500 + 300, (test, first[:3])  # within 30 s
    first = np.flatnonzero(alarms["cusum_alarm"])[0]
    assert alarms["cusum_isolated"][first] == 1  # theta_2, the tangential thruster
    assert alarms["cusum_direction"][first] == -1  # its efficiency dropped
    assert alarms["glr_isolated"][np.flatnonzero(alarms["glr_alarm"])[0]] == 1
    assert not alarms["chi_square_alarm"][:1500].any()
    assert np.all(alarms["status"][:MONITOR_FROM] == UpdateStatus.nonfinite_input)


def test_fault_free_runs_raise_about_the_designed_false_alarms(monitor_design):
    """Five fresh seeds of 3000 s: 4.2 false alarms per test expected at one an hour."""
    system, design, _ = monitor_design
    counts = np.zeros(3, int)
    for seed in range(101, 106):
        data = adaptobs.examples.simulate_satellite(31000, seed=seed)
        result = make_observer(system).run(data["U"], data["Y"], data["Psi"])
        status = result.status.copy()
        status[:MONITOR_FROM] = UpdateStatus.nonfinite_input
        alarms = adaptobs.FaultMonitor(design).run(result.parameters, result.output_error, status=status)
        counts += [alarms["cusum_alarm"].sum(), alarms["glr_alarm"].sum(), alarms["chi_square_alarm"].sum()]
    assert np.all(counts <= 15), counts


def test_run_equals_a_loop_of_observe_and_a_pickle_continues_bit_for_bit(monitor_design):
    system, design, _ = monitor_design
    U, Y, Psi = thruster_fault_data(system, 3000, fault_at=2000, seed=8)
    result = make_observer(system).run(U, Y, Psi)
    theta, error = result.parameters[MONITOR_FROM:], result.output_error[MONITOR_FROM:]
    batch = adaptobs.FaultMonitor(design).run(theta, error)
    stepped = adaptobs.FaultMonitor(design)
    for k in range(len(theta)):
        if k == 900:
            stepped = pickle.loads(pickle.dumps(stepped))
        if k == 1100:
            stepped = copy.deepcopy(stepped)
        assert stepped.observe(theta[k], error[k]) == UpdateStatus.accepted
        assert stepped.cusum.alarm == batch["cusum_alarm"][k], k
        assert stepped.glr.alarm == batch["glr_alarm"][k], k
        assert stepped.chi_square.alarm == batch["chi_square_alarm"][k], k
        assert stepped.cusum.statistic == batch["cusum_statistic"][k], k
        assert stepped.glr.statistic == batch["glr_statistic"][k], k
        assert stepped.chi_square.statistic == batch["chi_square_statistic"][k], k
    assert batch["cusum_alarm"].any()


def test_a_design_pickles_and_builds_the_same_monitor(monitor_design):
    system, design, parameters = monitor_design
    twin = pickle.loads(pickle.dumps(design))
    assert twin.cusum.threshold == design.cusum.threshold and twin.glr_threshold == design.glr_threshold
    assert np.array_equal(twin.output_error_covariance, design.output_error_covariance)
    theta, error = parameters[0][:3000], parameters[0][:3000] * 0.0
    a = adaptobs.FaultMonitor(design).run(theta, error)
    b = adaptobs.FaultMonitor(twin).run(theta, error)
    assert all(np.array_equal(a[key], b[key]) for key in a)


def test_the_cusum_is_page_s_recursion():
    rng = np.random.default_rng(1)
    nominal, scale, drift, threshold = np.array([1.0, -2.0]), np.array([0.5, 2.0]), 0.25, 4.0
    values = nominal + scale * (rng.standard_normal((400, 2)) + np.where(np.arange(400) >= 200, 1.0, 0.0)[:, None])
    cusum = adaptobs.CusumDetector(nominal, scale, drift, threshold)
    upper, lower = np.zeros(2), np.zeros(2)
    alarms = 0
    for v in values:
        z = (v - nominal) * (1 / scale)
        upper = np.maximum(0, upper + z - drift)
        lower = np.maximum(0, lower - z - drift)
        alarm = max(upper.max(), lower.max()) > threshold
        assert cusum.update(v) == UpdateStatus.accepted
        assert cusum.alarm == alarm
        if alarm:
            alarms += 1
            upper, lower = np.zeros(2), np.zeros(2)
        assert np.array_equal(cusum.upper, upper) and np.array_equal(cusum.lower, lower)
    assert cusum.alarm_count == alarms > 5


def test_the_glr_is_the_windowed_likelihood_ratio():
    rng = np.random.default_rng(2)
    nominal, scale, window, threshold = np.zeros(1), np.ones(1), 8, 6.0
    values = rng.standard_normal((300, 1)) + np.where(np.arange(300) >= 150, 1.5, 0.0)[:, None]
    glr = adaptobs.GlrDetector(nominal, scale, window, threshold)
    history = []
    for v in values:
        history.append(v[0])
        recent = history[-window:][::-1]
        sums = np.cumsum(recent)
        g = np.max(sums**2 / (2 * np.arange(1, len(recent) + 1)))
        glr.update(v)
        assert glr.statistic == pytest.approx(0.0 if g > threshold else g, abs=1e-12)
        assert glr.alarm == (g > threshold)
        if g > threshold:
            history = []
    assert glr.alarm_count > 3


def test_the_chi_square_test_sums_the_weighted_output_errors():
    S = np.array([[2.0, 0.3], [0.3, 1.0]])
    test = adaptobs.ChiSquareTest(S, window=5, false_alarm_probability=0.01)
    rng = np.random.default_rng(4)
    errors = rng.multivariate_normal(np.zeros(2), S, size=50)
    total = 0.0
    for k, e in enumerate(errors):
        total += e @ np.linalg.solve(S, e)
        test.update(e)
        if (k + 1) % 5 == 0:
            assert test.decision_statistic == pytest.approx(total, rel=1e-12)
            assert test.alarm == (total > test.threshold)
            total = 0.0
    assert test.decisions == 10
    # The 1 % upper quantile of chi^2 with 10 degrees of freedom.
    assert test.threshold == pytest.approx(23.209251158954356, rel=1e-9)


def test_detectors_survive_pickling():
    cusum = adaptobs.CusumDetector([0.0], [1.0], 0.5, 5.0, stride=3, hold_off=2)
    glr = adaptobs.GlrDetector([0.0, 0.0], [1.0, 2.0], 6, 7.0)
    chi = adaptobs.ChiSquareTest(np.eye(2), 4, 0.05)
    rng = np.random.default_rng(6)
    for detector, n in ((cusum, 1), (glr, 2), (chi, 2)):
        values = rng.standard_normal((200, n)) + 1.0
        for v in values[:77]:
            detector.update(v)
        twin = pickle.loads(pickle.dumps(detector))
        for v in values[77:]:
            detector.update(v)
            twin.update(v)
            assert detector.statistic == twin.statistic and detector.alarm == twin.alarm
        assert detector.alarm_count == twin.alarm_count > 0
    with pytest.raises(ConfigurationError, match="is of a GlrDetector, not of a CusumDetector"):
        cusum.restore(glr.snapshot())


def test_bad_detector_configuration_names_the_argument(monitor_design):
    system, design, parameters = monitor_design
    cases = [
        (lambda: adaptobs.CusumDetector([0.0], [1.0], -1.0, 5.0), "CusumDetector: argument 'drift'"),
        (lambda: adaptobs.CusumDetector([0.0], [0.0], 1.0, 5.0), "CusumDetector: argument 'scale'"),
        (lambda: adaptobs.CusumDetector([0.0], [1.0], 1.0, 5.0, stride=0), "CusumDetector: argument 'stride' must be at least 1"),
        (lambda: adaptobs.GlrDetector([0.0], [1.0], 0, 5.0), "GlrDetector: argument 'window'"),
        (lambda: adaptobs.CusumDetector([0.0], [1.0], 1.0, 5.0, hold_off=-1), "CusumDetector: argument 'hold_off'"),
        (lambda: adaptobs.ChiSquareTest(-np.eye(2), 4, 0.05), "ChiSquareTest: argument 'covariance'"),
        (lambda: adaptobs.ChiSquareTest(np.eye(2), 4, 1.5), "ChiSquareTest: argument 'false_alarm_probability'"),
        (lambda: adaptobs.design_fault_monitor(parameters, parameters[:3], system["theta"], 1.0, 36000.0, 100, 100),
         "design_fault_monitor: argument 'output_errors' must hold one array per run"),
        (lambda: adaptobs.design_fault_monitor(parameters, parameters, system["theta"], 1.0, 36000.0, 100, 40000),
         "design_fault_monitor: argument 'window'"),
        (lambda: adaptobs.FaultMonitor(design).observe([1.0, 1.5, 2.0], [0.0, 0.0]),
         "FaultMonitor.observe: argument 'parameters' must be (2,) (got (3,))"),
    ]
    for call, message in cases:
        with pytest.raises(ConfigurationError) as error:
            call()
        assert str(error.value).startswith(message), str(error.value)
    with pytest.raises(TypeError, match="GlrDetector: argument 'window' must be an integer \\(got float\\)"):
        adaptobs.GlrDetector([0.0], [1.0], 8.0, 5.0)
    with pytest.raises(TypeError, match="CusumDetector: argument 'reanchor' must be a bool"):
        adaptobs.CusumDetector([0.0], [1.0], 1.0, 5.0, reanchor="yes")
    assert adaptobs.CusumDetector([0.0], [1.0], np.float64(1.0), np.array(5.0), stride=np.int64(2),
                                  reanchor=np.True_).threshold == 5.0
    with pytest.raises(TypeError, match="FaultMonitor.run: argument 'status' must be an array of UpdateStatus values"):
        adaptobs.FaultMonitor(design).run(parameters[0][:10], parameters[0][:10], status=np.ones(10, bool))
    with pytest.raises(TypeError, match="FaultMonitor: argument 'design' must be an adaptobs.FaultMonitorDesign"):
        adaptobs.FaultMonitor({"nominal": [1.0, 1.5]})
    with pytest.raises(TypeError, match="design_fault_monitor: argument 'parameters' must be a list of arrays"):
        adaptobs.design_fault_monitor(3.0, parameters, system["theta"], 1.0, 36000.0, 100, 100)
    # A NaN estimate is a rejected sample, the tests unchanged.
    monitor = adaptobs.FaultMonitor(design)
    before = monitor.snapshot()
    assert monitor.observe([np.nan, 1.5], [0.0, 0.0]) == UpdateStatus.nonfinite_input
    after = monitor.snapshot()
    assert before["integers"] == after["integers"]
    assert all(np.array_equal(before["matrices"][k], after["matrices"][k]) for k in before["matrices"])


def ar1_runs(tau, runs, length, seed):
    """Fault-free runs whose estimates are AR(1) about (1.5, -0.3), correlation times `tau` (samples),
    standard deviation 0.01, and white unit output errors."""
    rng = np.random.default_rng(seed)
    phi = np.exp(-1.0 / np.asarray(tau, float))
    x = rng.standard_normal((runs, 2))
    noise = rng.standard_normal((length, runs, 2)) * np.sqrt(1 - phi**2)
    values = np.empty((length, runs, 2))
    for k in range(length):
        x = phi * x + noise[k]
        values[k] = x
    parameters = [np.array([1.5, -0.3]) + 0.01 * values[:, r, :] for r in range(runs)]
    errors = [rng.standard_normal((length, 1)) for _ in range(runs)]
    return parameters, errors


def test_the_design_chooses_the_stride_and_the_nominal_value():
    """Correlation times 40 and 10 samples: the stride where exp(-s/40) = 0.1 is 40 ln 10 = 92.1 samples."""
    parameters, errors = ar1_runs([40, 10], 40, 25000, seed=3)
    design = adaptobs.design_fault_monitor(parameters, errors, 1.0, 200.0 * 93, 100)
    assert 83 <= design.stride <= 103, design.explanation
    correlations = design.stride_correlations
    assert [c[0] for c in correlations] == list(range(1, design.stride + 1))
    assert correlations[-1][1] <= 0.1 and correlations[-1][2] <= 0.25
    assert correlations[-2][1] > 0.1 or correlations[-2][2] > 0.25  # the smallest
    assert correlations[design.stride // 2 - 1][1] > 0.25  # exp(-46/40) = 0.32
    at_stride = np.concatenate([p[:: design.stride] for p in parameters])
    assert np.allclose(design.nominal, at_stride.mean(axis=0), rtol=0, atol=1e-14)
    assert design.cusum.lag_correlation == correlations[-1][1]
    assert design.explanation.startswith(f"stride {design.stride} samples, the smallest")
    assert "nominal = mean of theta-hat at the stride" in design.explanation
    copied = pickle.loads(pickle.dumps(design))
    assert copied.explanation == design.explanation and copied.stride_correlations == correlations
    # A multiple of a period only.
    periodic = adaptobs.design_fault_monitor(parameters, errors, 1.0, 200.0 * 100, 100, stride_multiple=50)
    assert periodic.stride == 100 and [c[0] for c in periodic.stride_correlations] == [50, 100]


def test_a_bad_record_is_refused_naming_the_record_and_the_entry():
    """One NaN output error was refused as sample_covariance's 'runs', errors all zero as ChiSquareTest's
    'covariance'."""
    parameters, errors = ar1_runs([40, 10], 40, 25000, seed=3)
    errors = [e.copy() for e in errors]
    errors[2][3, 0] = np.nan
    for design in (lambda: adaptobs.design_fault_monitor(parameters, errors, 1.0, 200.0 * 93, 100),
                   lambda: adaptobs.design_fault_monitor(parameters, errors, [1.5, -0.3], 1.0, 200.0 * 100, 100, 100)):
        with pytest.raises(ConfigurationError) as error:
            design()
        assert str(error.value) == ("design_fault_monitor: argument 'record' holds an output error that is not "
                                    "finite: number 3 of run 2 (counted from 0)")
    zero = [np.zeros_like(e) for e in errors]
    with pytest.raises(ConfigurationError) as error:
        adaptobs.design_fault_monitor(parameters, zero, 1.0, 200.0 * 93, 100)
    message = str(error.value)
    assert message.startswith("design_fault_monitor: argument 'record' was refused at the stride found"), message
    assert "design_fault_monitor: argument 'record' has output errors whose sample covariance is singular" in message


def test_runs_too_short_for_the_stride_are_refused_with_the_remedy():
    """Correlation time 400 samples, 100 runs of 1500: the largest stride they support is 299, the stride
    needed about 921, so runs of about 5 x 921 + 1 = 4606 samples."""
    parameters, errors = ar1_runs([400, 10], 100, 1500, seed=4)
    with pytest.raises(ConfigurationError) as error:
        adaptobs.design_fault_monitor(parameters, errors, 1.0, 1e5, 10)
    message = str(error.value)
    assert message.startswith("design_fault_monitor: argument 'record' has runs too short"), message
    assert "at 299 samples, the largest stride they support" in message
    length = float(message.split("remedies: runs of at least ")[1].split()[0])
    assert 0.8 * 4606 <= length <= 1.25 * 4606, message
    assert "more runs of 1500 samples cannot help" in message
    assert "a step size mu about" in message
