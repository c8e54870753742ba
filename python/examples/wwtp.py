"""The waste water treatment plant of Srinivasarengan, Ragot, Aubrun & Maquin
(2018), section 6, from Python: the Takagi-Sugeno adaptive observer (65) with
the printed gains, figures 1-5 of the C++ example (examples/wwtp.cpp) with
matplotlib, optionally with lost outputs.

    python python/examples/wwtp.py [--out wwtp_python.png] [--steps 500] [--loss 0] [--no-figure]
"""

import argparse

import numpy as np

import adaptobs

B = 0.4  # b of Table 1, in the premise z2 = x1 / (x2 + b)


def premises(x, u, theta):
    """Premise variables (75): z1 = u, z2 = x1 / (x2 + b), at the observer's estimates."""
    return np.array([u[0], x[0] / (x[1] + B)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="wwtp_python.png")
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--loss", type=float, default=0.0, help="probability that an output is lost")
    parser.add_argument("--no-figure", action="store_true", help="print the estimates only")
    args = parser.parse_args()
    if not 2 <= args.steps <= 10**6:
        parser.error("--steps must lie in [2, 1e6]")
    if not 0.0 <= args.loss < 1.0:
        parser.error("--loss must lie in [0, 1)")

    w = adaptobs.examples.wwtp()
    data = adaptobs.examples.simulate_wwtp(args.steps)
    model = adaptobs.TakagiSugenoModel(w["vertices"], w["C"], premises, w["premise_bounds"], w["parameter_bounds"])
    observer = adaptobs.TakagiSugenoObserver(model, adaptobs.TakagiSugenoGains(w["L"], w["K"]), w["x0_estimate"],
                                             w["theta0_estimate"])
    present = np.random.default_rng(7).random((args.steps, 1)) >= args.loss
    result = observer.run(data["U"], data["Y"], present=present)
    print("theta_hat =", result.parameters[-1, 0], "against", w["theta"][0])
    print("state error =", np.linalg.norm(result.state[-2] - data["X"][-1]))  # row k: x_{k+1}
    print("lost outputs:", int(np.count_nonzero(~present)))
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = data["t"]
    fig, axes = plt.subplots(3, 2, figsize=(12, 9))
    for i, ax in enumerate(axes[0]):
        ax.plot(t, data["X"][:, i], "k", lw=2, label="plant")
        ax.plot(t[1:], result.state[:-1, i], label="observer (65)")
        ax.set_title(f"Figure {i + 1}: estimation of x{i + 1}")
        ax.legend(loc="upper right")
    axes[1, 0].plot(t, data["theta"][:, 0], "k", lw=2, label="true")
    axes[1, 0].plot(t, result.parameters[:, 0], label="estimate")
    axes[1, 0].set_title("Figure 3: estimation of theta")
    axes[1, 0].legend(loc="lower right")
    axes[1, 1].plot(t, data["U"][:, 0])
    axes[1, 1].set_title("Figure 4: input (dilution rate)")
    axes[2, 0].plot(t, np.array(list(_weights(w, model, data, present))))
    axes[2, 0].set_title("Figure 5: weights h_i")
    axes[2, 1].axis("off")
    for ax in axes.flat:
        ax.set_xlabel("t (h)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


def _weights(w, model, data, present):
    """The weights h_i of each update, from a twin observer stepped sample by sample."""
    twin = adaptobs.TakagiSugenoObserver(model, adaptobs.TakagiSugenoGains(w["L"], w["K"]), w["x0_estimate"],
                                         w["theta0_estimate"])
    for k in range(len(data["Y"])):
        twin.update(data["U"][k], data["Y"][k], present=present[k])
        yield twin.weights


if __name__ == "__main__":
    main()
