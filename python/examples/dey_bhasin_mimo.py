"""The MIMO example of Dey & Bhasin (2022), section 5, from Python: the
adaptive observer under an input that is not sufficiently rich and under one
that is, figures 1-3 of the C++ example (examples/dey_bhasin_mimo.cpp) with
matplotlib.

    python python/examples/dey_bhasin_mimo.py [--out dey_bhasin_python.png] [--steps 300] [--no-figure]
"""

import argparse

import numpy as np

import adaptobs


def normalized_estimates(parameters, system):
    """Each estimate of a and B over its true value, per sample: 1 once identified (figure 1).
    The observer's parameters are (a - f, vec B), B by columns."""
    a_hat = parameters[:, :3] + system["f"]
    b_hat = parameters[:, 3:]
    return np.hstack([a_hat / system["a"], b_hat / system["B"].reshape(-1, order="F")])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="dey_bhasin_python.png")
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--no-figure", action="store_true", help="print the estimates only")
    args = parser.parse_args()
    if not 10 <= args.steps <= 10**6:
        parser.error("--steps must lie in [10, 1e6]")

    m = adaptobs.examples.dey_bhasin_mimo()
    runs = {}
    for rich in (False, True):
        data = adaptobs.examples.simulate_dey_bhasin_mimo(args.steps, rich=rich)
        observer = adaptobs.DeyBhasinObserver(m["f"], m["x0_estimate"], m["a0_estimate"], m["B0_estimate"],
                                              k0=m["k0"], kmin=m["kmin"], R=m["R"])
        result = observer.run(data["U"], data["Y"])
        runs[rich] = (data, result, normalized_estimates(result.parameters, m))
        worst = np.max(np.abs(runs[rich][2][-1] - 1))
        print(f"{'rich' if rich else 'not rich'} input: largest |estimate / true - 1| = {worst:.3g}, "
              f"resets = {int(result.diagnostics['reset_count'][-1])}")
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 2, figsize=(12, 10), sharex=True)
    for column, rich in enumerate((False, True)):
        data, result, normalized = runs[rich]
        t = np.arange(args.steps)
        which = "sufficiently rich input" if rich else "input not sufficiently rich"
        axes[0, column].plot(t, normalized)
        axes[0, column].set_ylim(-1, 3)
        axes[0, column].set_title(f"Figure 1({'ab'[column]}): normalized estimates, {which}")
        # Row t of the run is x_hat_{t+1|t}: against the true state of step t + 1.
        axes[1, column].plot(t[1:], np.linalg.norm(result.state[:-1] - data["X"][1:], axis=1))
        axes[1, column].set_yscale("log")
        axes[1, column].set_title(f"Figure 2: ||x - x_hat||, {which}")
        axes[2, column].plot(t, data["U"], label=["u1", "u2"])
        axes[2, column].set_title(f"Figure 3({'ab'[column]}): {which}")
        axes[2, column].legend(loc="upper right")
        axes[2, column].set_xlabel("t (samples)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
