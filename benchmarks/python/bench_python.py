"""Cost of the Python package against the same observers in C++, in one run.

For the satellite of Guyader & Zhang (2003) with run-time sizes:
- update() from Python, per sample;
- run() over N samples, per sample;
- a C++ loop of update() over the same samples (cxx_dynamic_loop.cpp, built
  here with the flags of the package's Release build, -O3 -DNDEBUG);
and the import time of the package and the size of its extension module.
Each figure is the minimum of several repetitions; compare the ratios, which
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


def best_of(repetitions, function):
    best = float("inf")
    for _ in range(repetitions):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


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
    system = adaptobs.examples.satellite()
    data = adaptobs.examples.simulate_satellite(n)
    model = adaptobs.DiscreteLtiModel(system["A"], system["B"], system["C"], np=2)

    def guyader_zhang():
        return adaptobs.GuyaderZhangObserver(model, system["K"], system["mu"], system["x0_estimate"],
                                             system["theta0_estimate"])

    def augmented_kalman():
        p0 = np.diag([0.1, 1e-4, 0.1, 1e-4, 1.0, 1.0])
        q = np.diag([1e-10] * 4 + [0.0, 0.0])
        return adaptobs.AugmentedKalmanFilter(model, system["x0_estimate"], system["theta0_estimate"], P0=p0, Q=q,
                                              R=np.eye(2) * 1e-4)

    with tempfile.TemporaryDirectory() as scratch:
        binary = os.path.join(scratch, "cxx_dynamic_loop")
        subprocess.run(["g++", "-std=c++20", "-O3", "-DNDEBUG", f"-I{root}/include", f"-I{root}/examples",
                        "-I/usr/include/eigen3", os.path.join(root, "benchmarks/python/cxx_dynamic_loop.cpp"),
                        "-o", binary], check=True)
        cxx = dict(line.split() for line in subprocess.run([binary, str(n)], check=True, capture_output=True,
                                                           text=True).stdout.splitlines())

    U, Y, Psi = data["U"], data["Y"], data["Psi"]
    steps = min(n, 20_000)
    print(f"{'observer':<24}{'update() ns':>12}{'run() ns':>10}{'C++ ns':>9}{'run/C++':>9}{'update-C++ us':>15}")
    for name, make in (("GuyaderZhangObserver", guyader_zhang), ("AugmentedKalmanFilter", augmented_kalman)):
        def python_loop():
            o = make()
            update = o.update
            for k in range(steps):
                update(U[k], Y[k], Psi[k])

        step_ns = best_of(3, python_loop) / steps * 1e9
        run_ns = best_of(5, lambda: make().run(U, Y, Psi)) / n * 1e9
        cxx_ns = float(cxx[name])
        print(f"{name:<24}{step_ns:>12.0f}{run_ns:>10.1f}{cxx_ns:>9.1f}{run_ns / cxx_ns:>9.2f}"
              f"{(step_ns - cxx_ns) / 1e3:>15.2f}")

    # Two threads running run() at once against the same two runs in one thread (the GIL is released).
    import threading

    big = 1_000_000
    U1, Y1 = np.zeros((big, 2)), np.zeros((big, 2))

    def one():
        guyader_zhang().run(U1, Y1, None)

    sequential = best_of(3, lambda: (one(), one()))

    def threaded():
        threads = [threading.Thread(target=one) for _ in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()

    parallel = best_of(3, threaded)
    print(f"two 10^6-sample runs: {sequential:.3f} s in one thread, {parallel:.3f} s in two "
          f"(ratio {parallel / sequential:.2f})")
    print(f"import adaptobs: {import_ms:.1f} ms; extension module {os.path.getsize(module) / 1e6:.2f} MB "
          f"({os.path.basename(module)}, Python {sysconfig.get_python_version()})")


if __name__ == "__main__":
    sys.exit(main())
