"""Cost of the Python package against the same observers in C++, in one run.

For the satellite of Guyader & Zhang (2003) (Guyader-Zhang and the augmented
Kalman filter), the MIMO example of Dey & Bhasin (2022) and the third-order
plant of the unified formulation (Bastin-Gevers, its regressor a Python
callable), with run-time sizes:
- update() from Python, per sample;
- run() over N samples, per sample;
- a C++ loop of update() over the same samples keeping what run() returns
  (cxx_dynamic_loop.cpp, built here with the flags of the package's Release
  build, -O3 -DNDEBUG);
two 10^6-sample runs in two threads against one thread, the import time of the
package and the size of its extension module.
Each figure is the minimum of several repetitions, in CPU time of the process
(the C++ loop's too), the two-thread runs in wall time; compare the ratios, which
come from the same run.

    build/venv/bin/python benchmarks/python/bench_python.py [--samples 100000]
"""

import argparse
import os
import subprocess
import sys
import sysconfig
import tempfile
import time

import numpy as np


def best_of(repetitions, function, clock=time.process_time):
    """The least time of `function` over `repetitions` calls, by default in CPU time of this process (as
    cxx_dynamic_loop.cpp measures its loop); the wall clock for the runs on two threads."""
    best = float("inf")
    for _ in range(repetitions):
        start = clock()
        function()
        best = min(best, clock() - start)
    return best


def observers(n):
    """Each observer of the table: a factory, the arguments of run() and the number of samples."""
    import math

    import adaptobs

    s = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(n)
    model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
    satellite = (data["U"], data["Y"], data["Psi"])

    def guyader_zhang():
        return adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"])

    def augmented_kalman():
        return adaptobs.AugmentedKalmanFilter(model, s["x0_estimate"], s["theta0_estimate"],
                                              P0=np.diag([0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0]),
                                              Q=np.diag([1e-10] * 4 + [0.0, 0.0]), R=np.eye(2) * 1e-4)

    m = adaptobs.examples.dey_bhasin_mimo()
    db_samples = min(n, 20_000)
    mimo = adaptobs.examples.simulate_dey_bhasin_mimo(db_samples)

    def dey_bhasin():
        return adaptobs.DeyBhasinObserver(m["f"], m["x0_estimate"], m["a0_estimate"], m["B0_estimate"], k0=m["k0"],
                                          kmin=m["kmin"], R=m["R"])

    p = adaptobs.examples.siso()
    siso = adaptobs.examples.simulate_siso(n)

    def phi(t):  # Phi(t) of the third-order plant, called at every Runge-Kutta stage
        return np.array([[math.sin(t), 0.0], [math.cos(1.7 * t), 1.0], [0.0, math.sin(0.6 * t)]])

    transform = adaptobs.bastin_gevers_form(p["A"], p["C"], [1.0, 4.0, 3.0])
    so = transform.apply(p["A"], p["B"], p["C"])
    k = adaptobs.spr_injection_gain(so["Ao"], so["Co"], [1.0, 0.0, 0.0], 2.0)
    continuous = adaptobs.ContinuousLtiModel(p["A"], p["B"], p["C"], phi, np=2)

    def bastin_gevers():
        return adaptobs.BastinGeversObserver(continuous, transform, k, 5.0 * np.eye(2), np.zeros(3), np.zeros(2),
                                             input="quadratic", output="quadratic")

    return {
        "GuyaderZhangObserver": (guyader_zhang, satellite, n),
        "AugmentedKalmanFilter": (augmented_kalman, satellite, n),
        "DeyBhasinObserver": (dey_bhasin, (mimo["U"], mimo["Y"]), db_samples),
        "BastinGeversObserver": (bastin_gevers, (siso["t"], siso["U"], siso["Y"], siso["U_mid"], siso["Y_mid"]), n),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=100_000)
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

    start = time.perf_counter()
    import adaptobs  # noqa: E402  (timed)

    import_ms = (time.perf_counter() - start) * 1e3
    module = adaptobs._core.__file__

    n = args.samples
    cases = observers(n)

    compiler = os.environ.get("CXX", "c++")
    eigen = subprocess.run(["pkg-config", "--cflags", "eigen3"], capture_output=True, text=True).stdout.split() \
        or ["-I/usr/include/eigen3"]
    with tempfile.TemporaryDirectory() as scratch:
        binary = os.path.join(scratch, "cxx_dynamic_loop")
        subprocess.run([compiler, "-std=c++20", "-O3", "-DNDEBUG", f"-I{root}/include", f"-I{root}/examples", *eigen,
                        os.path.join(root, "benchmarks/python/cxx_dynamic_loop.cpp"), "-o", binary], check=True)
        cxx = dict(line.split() for line in subprocess.run([binary, str(n)], check=True, capture_output=True,
                                                           text=True).stdout.splitlines())

    print(f"{'observer':<24}{'samples':>8}{'update() ns':>12}{'run() ns':>10}{'C++ ns':>9}{'run/C++':>9}"
          f"{'update - C++ us':>17}")
    for name, (make, arguments, samples) in cases.items():
        steps = min(samples, 20_000)

        def python_loop():
            o = make()
            update = o.update
            rows = [tuple(None if a is None else a[k] for a in arguments) for k in range(steps)]
            start = time.process_time()
            for row in rows:
                update(*row)
            return time.process_time() - start

        step_ns = min(python_loop() for _ in range(3)) / steps * 1e9
        run_ns = best_of(5, lambda: make().run(*arguments)) / samples * 1e9
        cxx_ns = float(cxx[name])
        print(f"{name:<24}{samples:>8}{step_ns:>12.0f}{run_ns:>10.1f}{cxx_ns:>9.1f}{run_ns / cxx_ns:>9.2f}"
              f"{(step_ns - cxx_ns) / 1e3:>17.2f}")

    # Two threads running run() at once against the same two runs in one thread (the GIL is released).
    import threading

    big = 1_000_000
    U1, Y1 = np.zeros((big, 2)), np.zeros((big, 2))

    make_gz = cases["GuyaderZhangObserver"][0]
    psi = np.zeros((4, 2))

    def one():
        make_gz().run(U1, Y1, psi)

    sequential = best_of(3, lambda: (one(), one()), clock=time.perf_counter)

    def threaded():
        threads = [threading.Thread(target=one) for _ in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()

    parallel = best_of(3, threaded, clock=time.perf_counter)
    print(f"two 10^6-sample runs: {sequential:.3f} s in one thread, {parallel:.3f} s in two "
          f"(ratio {parallel / sequential:.2f})")
    print(f"import adaptobs: {import_ms:.1f} ms; extension module {os.path.getsize(module) / 1e6:.2f} MB "
          f"({os.path.basename(module)}, Python {sysconfig.get_python_version()})")


if __name__ == "__main__":
    sys.exit(main())
