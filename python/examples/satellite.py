"""The satellite of Guyader & Zhang (2003), section 4, from Python: the
Guyader-Zhang observer beside the augmented Kalman filter, figures 1-3 of the
C++ example (examples/satellite.cpp) with matplotlib.

    python python/examples/satellite.py [--out satellite_python.png] [--seed 2003] [--seconds 300] [--no-figure]
"""

import argparse

import numpy as np

import adaptobs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="satellite_python.png")
    parser.add_argument("--seed", type=int, default=2003)
    parser.add_argument("--seconds", type=float, default=300.0)
    parser.add_argument("--no-figure", action="store_true", help="print the estimates only")
    args = parser.parse_args()
    if not 1.0 <= args.seconds <= 1e6:
        parser.error("--seconds must lie in [1, 1e6]")

    s = adaptobs.examples.satellite()
    steps = int(round(args.seconds / s["Ts"]))
    data = adaptobs.examples.simulate_satellite(steps, noise=0.01, seed=args.seed)
    model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
    observer = adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"],
                                             excitation_window=100)
    akf = adaptobs.AugmentedKalmanFilter(model, s["x0_estimate"], s["theta0_estimate"],
                                         P0=np.diag([0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0]),
                                         Q=np.diag([1e-10] * 4 + [0.0, 0.0]), R=np.eye(2) * 1e-4)
    gz = observer.run(data["U"], data["Y"], data["Psi"])
    kf = akf.run(data["U"], data["Y"], data["Psi"])
    print("theta_hat =", gz.parameters[-1], "against", s["theta"])
    print("mean over the last 100 s =", gz.parameters[-1000:].mean(axis=0))
    print("augmented Kalman filter mean =", kf.parameters[-1000:].mean(axis=0))
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.arange(steps) * s["Ts"]
    fig, axes = plt.subplots(3, 1, figsize=(10, 9), sharex=True)
    axes[0].plot(t, data["U"], label=["u1 radial", "u2 tangential"])
    axes[0].set_title("Figure 1: thrusts")
    axes[0].legend(loc="upper right")
    axes[1].plot(t[1:], gz.state[:-1] - data["X"][1:], label=[f"error x{i}" for i in range(1, 5)])  # row k: x_{k+1}
    axes[1].legend(loc="upper right", ncol=4)
    axes[1].set_ylim(-0.06, 0.06)
    axes[1].set_title("Figure 2: state estimation errors")
    axes[2].plot(t, gz.parameters, label=["theta1 adaptive observer", "theta2 adaptive observer"])
    axes[2].plot(t, kf.parameters, "--", label=["theta1 augmented KF", "theta2 augmented KF"])
    axes[2].axhline(1.0, color="k", ls=":")
    axes[2].axhline(1.5, color="k", ls=":")
    axes[2].set_ylim(0, 2)
    axes[2].set_title("Figure 3: parameter estimates (true 1 and 1.5)")
    axes[2].legend(loc="lower right")
    axes[2].set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
