"""A thruster fault on the satellite of Guyader & Zhang (2003), from Python: a
FaultMonitor designed from 20 fault-free runs (false alarms once an hour per
test) watches the Guyader-Zhang observer while the tangential thruster loses
40 % of its efficiency at t = 150 s. The figure shows theta_hat and the CUSUM
statistic against its threshold (the C++ example: examples/satellite_fault.cpp).

    python python/examples/satellite_fault.py [--out satellite_fault_python.png] [--no-figure]
"""

import argparse

import numpy as np

import adaptobs

MONITOR_FROM = 1000  # samples (100 s): the estimates have converged


def observer(s):
    model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
    return adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"])


def faulty_outputs(s, data, fault_at, size, seed):
    """The satellite's outputs with theta_2 scaled by 1 + size from sample fault_at, noise 0.01."""
    rng = np.random.default_rng(seed)
    x = s["x0"].copy()
    Y = np.empty((len(data["U"]), 2))
    for k in range(len(Y)):
        theta = s["theta"] * np.array([1.0, 1.0 + size if k >= fault_at else 1.0])
        Y[k] = s["C"] @ x + 0.01 * rng.standard_normal(2)
        x = s["A"] @ x + data["Psi"][k] @ theta
    return Y


def fault_free_design(s):
    """A FaultMonitor designed from 20 fault-free runs of 3100 s (false alarms once an hour per test), and
    the parameter estimates of those runs from MONITOR_FROM on."""
    parameters, errors = [], []
    for seed in range(1, 21):
        data = adaptobs.examples.simulate_satellite(31000, seed=seed)
        result = observer(s).run(data["U"], data["Y"], data["Psi"])
        parameters.append(result.parameters[MONITOR_FROM:])
        errors.append(result.output_error[MONITOR_FROM:])
    design = adaptobs.design_fault_monitor(parameters, errors, s["theta"], drift=1.0,
                                           mean_samples_between_false_alarms=36000.0, stride=100, window=100)
    return design, parameters


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="satellite_fault_python.png")
    parser.add_argument("--no-figure", action="store_true", help="print the figures of merit only")
    parser.add_argument("--fault-size", type=float, default=-0.4, help="relative change of theta_2 (> -1)")
    args = parser.parse_args()
    if not -1.0 < args.fault_size < 10.0:
        parser.error("--fault-size must lie in (-1, 10): theta_2 stays positive")

    s = adaptobs.examples.satellite()
    design, _ = fault_free_design(s)
    print(f"CUSUM threshold {design.cusum.threshold:.3f}, GLR threshold {design.glr_threshold:.3f}")

    data = adaptobs.examples.simulate_satellite(3000, noise=0.0)
    fault_at = 1500
    Y = faulty_outputs(s, data, fault_at, args.fault_size, seed=5)
    result = observer(s).run(data["U"], Y, data["Psi"])
    status = result.status.copy()
    status[:MONITOR_FROM] = adaptobs.UpdateStatus.nonfinite_input  # not monitored before convergence
    alarms = adaptobs.FaultMonitor(design).run(result.parameters, result.output_error, status=status)
    for test in ("cusum", "glr", "chi_square"):
        raised = np.flatnonzero(alarms[f"{test}_alarm"])
        delay = f"{(raised[0] - fault_at) * s['Ts']:.1f} s after the fault" if raised.size else "no alarm"
        print(f"{test}: {delay}")
    first = np.flatnonzero(alarms["cusum_alarm"])
    if first.size:
        print(f"isolated: theta_{int(alarms['cusum_isolated'][first[0]]) + 1}, "
              f"direction {int(alarms['cusum_direction'][first[0]]):+d}")
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.arange(len(Y)) * s["Ts"]
    fig, axes = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    axes[0].plot(t, result.parameters, label=["theta1 estimate", "theta2 estimate"])
    axes[0].axvline(fault_at * s["Ts"], color="k", ls=":", label="fault")
    axes[0].set_ylim(0, 2)
    axes[0].legend(loc="lower left")
    axes[0].set_title("Parameter estimates: theta2 drops at t = 150 s")
    axes[1].plot(t, alarms["cusum_statistic"], label="CUSUM statistic (cleared at each alarm)")
    axes[1].axhline(design.cusum.threshold, color="r", ls="--", label="threshold")
    axes[1].plot(t[first], alarms["cusum_statistic"][first] * 0 + design.cusum.threshold, "rv", label="alarms")
    axes[1].legend(loc="center left")
    axes[1].set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
