"""The example of Guiro, Iggidr, Ngom & Toure (2008), section 4, from Python:
gains placed by design_guiro_gains, figures 1-2 of the C++ example
(examples/guiro.cpp) with matplotlib, optionally with lost samples.

    python python/examples/guiro.py [--out guiro_python.png] [--samples 60] [--loss 0] [--no-figure]
"""

import argparse

import numpy as np

import adaptobs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="guiro_python.png")
    parser.add_argument("--samples", type=int, default=60)
    parser.add_argument("--loss", type=float, default=0.0, help="probability that a sample is lost")
    parser.add_argument("--no-figure", action="store_true", help="print the estimates only")
    args = parser.parse_args()
    if not 2 <= args.samples <= 10**6:
        parser.error("--samples must lie in [2, 1e6]")
    if not 0.0 <= args.loss < 1.0:
        parser.error("--loss must lie in [0, 1)")

    g = adaptobs.examples.guiro()
    data = adaptobs.examples.simulate_guiro(args.samples)
    gains = adaptobs.design_guiro_gains(g["E"], g["C"], g["H0"], g["poles"])
    model = adaptobs.DiscreteLtiModel(g["E"], g["B"], g["C"], np=1)
    observer = adaptobs.GuiroObserver(model, gains.K, gains.Gamma, g["z0"], g["theta0"],
                                      correct_initial_estimate=False)
    present = np.random.default_rng(1).random((args.samples, 1)) >= args.loss
    result = observer.run(None, data["Y"], data["Psi"], present=present)
    print("K =", gains.K[:, 0], "Gamma =", gains.Gamma[0, 0], "spectral radius =", gains.spectral_radius)
    print("theta_hat =", result.parameters[-1, 0], "against", g["theta"][0])
    print("lost samples:", int(np.count_nonzero(~present)))
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = np.arange(args.samples) * g["T"]
    fig, axes = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    axes[0].plot(t, data["X"][:, 0], lw=2, label="x1")
    axes[0].plot(t[1:], result.state[:-1, 0], "o-", ms=3, label="prediction of x1")  # row k: z-_{k+1}
    axes[0].set_title("Figure 1: state x1 and its estimate")
    axes[0].legend(loc="upper right")
    axes[1].plot(t, result.parameters[:, 0], "o-", ms=3, label="theta estimate")
    axes[1].axhline(g["theta"][0], color="k", ls=":", label="theta = 5")
    axes[1].set_ylim(-3, 12)
    axes[1].set_title("Figure 2: parameter estimate")
    axes[1].legend(loc="lower right")
    axes[1].set_xlabel("t (T = 1)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
