"""The five continuous-time estimators of the unified formulation of Zhang
(2005) on the third-order plant, from Python: Algorithms 1-4 (Bastin-Gevers,
Marino-Tomei, Besancon, Zhang) and the Kalman-Bucy filter on [x; theta], the
figure of the C++ example (examples/unified_comparison.cpp) with matplotlib.
The designs below are also those the Python tests use.

    python python/examples/unified.py [--out unified_python.png] [--seconds 100] [--noise 0] [--no-figure]
"""

import argparse
import math

import numpy as np

import adaptobs


def regressor(t):
    """Phi(t) of the third-order plant, with the C library's sin and cos as in C++."""
    return np.array([[math.sin(t), 0.0], [math.cos(1.7 * t), 1.0], [0.0, math.sin(0.6 * t)]])


def model(system, phi=regressor):
    return adaptobs.ContinuousLtiModel(system["A"], system["B"], system["C"], phi, np=2)


def bastin_gevers(system, **options):
    transform = adaptobs.bastin_gevers_form(system["A"], system["C"], [1.0, 4.0, 3.0])  # (s + 1)(s + 3)
    so = transform.apply(system["A"], system["B"], system["C"])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], [1.0, 0.0, 0.0], 2.0)
    return adaptobs.BastinGeversObserver(model(system), transform, k, 5.0 * np.eye(2), np.zeros(3), np.zeros(2),
                                         input="quadratic", output="quadratic", **options)


def marino_tomei(system, **options):
    transform = adaptobs.marino_tomei_form(system["A"], system["C"])
    so = transform.apply(system["A"], system["B"], system["C"])
    gamma = np.array([1.0, 3.0, 2.0])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], gamma, 5.0)
    return adaptobs.MarinoTomeiObserver(model(system), transform, gamma, k, 20.0 * np.eye(2), np.zeros(3),
                                        np.zeros(2), input="quadratic", output="quadratic", **options)


def besancon(system, **options):
    transform = adaptobs.besancon_form(system["A"], system["C"])
    return adaptobs.BesanconObserver(model(system), transform, [[2.0]], 5.0 * np.eye(2), np.zeros(3), np.zeros(2),
                                     input="quadratic", output="quadratic", **options)


def zhang(system, **options):
    K = adaptobs.kalman_bucy_gain(system["A"], system["C"], np.eye(3), [[0.1]]).K
    return adaptobs.ZhangContinuousObserver(model(system), K, 20.0 * np.eye(2), np.zeros(3), np.zeros(2),
                                            input="quadratic", output="quadratic", **options)


def kalman_bucy(system, **options):
    q = np.eye(5)
    q[3:, 3:] *= 1e-2
    return adaptobs.AugmentedKalmanBucyFilter(model(system), np.zeros(3), np.zeros(2), np.eye(5), q, [[0.1]],
                                              input="quadratic", output="quadratic", **options)


def run(observer, data, n=None):
    n = len(data["t"]) if n is None else n
    return observer.run(data["t"][:n], data["U"][:n], data["Y"][:n], data["U_mid"][:n], data["Y_mid"][:n])


ESTIMATORS = {"Alg. 1 Bastin-Gevers": bastin_gevers, "Alg. 2 Marino-Tomei": marino_tomei,
              "Alg. 3 Besancon": besancon, "Alg. 4 Zhang": zhang, "Kalman-Bucy on [x; theta]": kalman_bucy}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="unified_python.png")
    parser.add_argument("--seconds", type=float, default=100.0)
    parser.add_argument("--noise", type=float, default=0.0, help="standard deviation of the output noise")
    parser.add_argument("--no-figure", action="store_true", help="print the estimates only")
    args = parser.parse_args()
    if not 1.0 <= args.seconds <= 1e5:
        parser.error("--seconds must lie in [1, 1e5]")
    if not 0.0 <= args.noise <= 1.0:
        parser.error("--noise must lie in [0, 1]")

    system = adaptobs.examples.siso()
    data = adaptobs.examples.simulate_siso(int(round(args.seconds / 0.01)) + 1, noise=args.noise)
    results = {name: run(make(system), data) for name, make in ESTIMATORS.items()}
    for name, result in results.items():
        error = np.linalg.norm(result.parameters[-1] - system["theta"])
        print(f"{name}: theta_hat = {result.parameters[-1]}, error {error:.2e}")
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(10, 10), sharex=True)
    for name, result in results.items():
        axes[0].plot(data["t"], result.parameters[:, 0], lw=1.5, label=name)
        axes[1].plot(data["t"], result.parameters[:, 1], lw=1.5, label=name)
        axes[2].semilogy(data["t"], np.linalg.norm(result.parameters - system["theta"], axis=1), lw=1.5, label=name)
    for ax, truth, title in zip(axes[:2], system["theta"], ("theta^1 (true 2)", "theta^2 (true -1)")):
        ax.axhline(truth, color="k", ls=":")
        ax.set_title(title)
    axes[2].set_title("parameter estimation error |estimate - theta|")
    axes[0].legend(loc="lower right", fontsize=8)
    axes[2].set_xlabel("t (s)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
