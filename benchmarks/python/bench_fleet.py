"""Throughput of adaptobs.fleet: asset-samples per second for the Guyader-Zhang satellite and the
Dey-Bhasin MIMO system, against the plain C++ loop and the Python run() on one core, and the cost of
checkpoints.

- C++ loop: benchmarks/python/cxx_dynamic_loop.cpp (the observer alone, run-time sizes, -O3);
- run(): the observer's run() over one asset's samples, from Python, on one core;
- run() + monitor: the same and FaultMonitor.run() over its estimates (what the fleet does per asset);
- fleet serial: adaptobs.fleet.process over the fleet's pandas DataFrame in this process;
- fleet 1 and 2 workers: the same from Parquet files (one per group of assets) on a LocalCluster of
  that many single-threaded worker processes (both clusters up at once); the wall-clock time from
  submission to the gathered result, reading the files included, the cluster's start excluded;
- checkpoints every K samples: fleet serial writing each asset's checkpoint to a local directory.
Each figure is the best of a few repetitions, the cases of one system measured round-robin; the
in-process cases and the C++ loop (the best of its five passes) in CPU time of their process, the
cluster cases in wall time. The machine's other load moves the figures; compare the ratios of one run.

    python benchmarks/python/bench_fleet.py [--assets 64] [--samples 10000]
"""

import argparse
import contextlib
import os
import subprocess
import sys
import tempfile
import time

import numpy as np


def best_of(repetitions, function, clock=time.process_time):
    """The least time of `function` over `repetitions` calls: by default the CPU time of this process
    (user and system: on a shared machine, far steadier than the wall clock), the wall clock for work
    done by other processes."""
    best = float("inf")
    for _ in range(repetitions):
        start = clock()
        function()
        best = min(best, clock() - start)
    return best


def satellite_fleet(assets, samples):
    """The satellite's observer, a FaultMonitor designed from 8 fault-free runs, and `assets` satellites'
    telemetry (seed 100 + asset)."""
    import pandas as pd

    import adaptobs
    from adaptobs import fleet

    s = adaptobs.examples.satellite()

    def observer():
        model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
        return adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"])

    parameters, errors = [], []
    for seed in range(1, 9):
        data = adaptobs.examples.simulate_satellite(12000, seed=seed)
        result = observer().run(data["U"], data["Y"], data["Psi"])
        parameters.append(result.parameters[1000:])
        errors.append(result.output_error[1000:])
    design = adaptobs.design_fault_monitor(parameters, errors, s["theta"], drift=1.0,
                                           mean_samples_between_false_alarms=36000.0, stride=100, window=100)
    frames = []
    for asset in range(assets):
        data = adaptobs.examples.simulate_satellite(samples, seed=100 + asset)
        columns = {"asset_id": np.full(samples, asset), "t": np.arange(samples) * 0.1}
        columns.update({f"u_{i}": data["U"][:, i] for i in range(2)})
        columns.update({f"y_{i}": data["Y"][:, i] for i in range(2)})
        columns.update({f"psi_{i}_{j}": data["Psi"][:, i, j] for i in range(4) for j in range(2)})
        frames.append(pd.DataFrame(columns))
    return fleet.AssetConfig(observer(), design, monitor_from=1000), pd.concat(frames, ignore_index=True)


def dey_bhasin_fleet(assets, samples):
    """The Dey-Bhasin MIMO observer, a FaultMonitor on its 15 parameters (thresholds of the satellite's
    design; the noise-free system gives no fault-free spread to design from, and the cost does not depend
    on them) and `assets` copies of the system's telemetry, each with its own small output noise."""
    import pandas as pd

    import adaptobs
    from adaptobs import fleet

    m = adaptobs.examples.dey_bhasin_mimo()
    observer = adaptobs.DeyBhasinObserver(m["f"], m["x0_estimate"], m["a0_estimate"], m["B0_estimate"], k0=m["k0"],
                                          kmin=m["kmin"], R=m["R"])
    template, _ = satellite_fleet(1, 2000)
    state = template.design.__getstate__()
    state.update(nominal=observer.run(*_dey_bhasin_data(samples)).parameters[-1], scale=np.ones(15))
    design = adaptobs.FaultMonitorDesign.__new__(adaptobs.FaultMonitorDesign)
    design.__setstate__(state)
    U, Y = _dey_bhasin_data(samples)
    frames = []
    for asset in range(assets):
        noisy = Y + 1e-4 * np.random.default_rng(asset).standard_normal(Y.shape)
        columns = {"asset_id": np.full(samples, asset), "t": np.arange(samples, dtype=float)}
        columns.update({f"u_{i}": U[:, i] for i in range(2)})
        columns.update({f"y_{i}": noisy[:, i] for i in range(2)})
        frames.append(pd.DataFrame(columns))
    return fleet.AssetConfig(observer, design, monitor_from=100), pd.concat(frames, ignore_index=True)


def _dey_bhasin_data(samples):
    import adaptobs

    data = adaptobs.examples.simulate_dey_bhasin_mimo(samples)
    return data["U"], data["Y"]


def cxx_loop(root, samples):
    """ns per sample of the C++ loop, per observer."""
    compiler = os.environ.get("CXX", "c++")
    eigen = subprocess.run(["pkg-config", "--cflags", "eigen3"], capture_output=True, text=True).stdout.split() \
        or ["-I/usr/include/eigen3"]
    with tempfile.TemporaryDirectory() as scratch:
        binary = os.path.join(scratch, "cxx_dynamic_loop")
        subprocess.run([compiler, "-std=c++20", "-O3", "-DNDEBUG", f"-I{root}/include", f"-I{root}/examples", *eigen,
                        os.path.join(root, "benchmarks/python/cxx_dynamic_loop.cpp"), "-o", binary], check=True)
        out = subprocess.run([binary, str(samples)], check=True, capture_output=True, text=True).stdout
    return {name: float(value) for name, value in (line.split() for line in out.splitlines())}


def one_asset(config, frame):
    """The arguments of run() for the fleet's first asset."""
    from adaptobs import fleet

    layout = fleet._layout(frame.columns, {}, config, "asset_id", "t")
    rows = frame[frame["asset_id"] == 0]
    _, U, Y, Psi = fleet._asset_arrays(rows, layout, 0)
    return U, Y, Psi


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--assets", type=int, default=64)
    parser.add_argument("--samples", type=int, default=10_000)
    parser.add_argument("--repetitions", type=int, default=3)
    args = parser.parse_args()
    if args.assets < 2 or args.samples < 2000:
        parser.error("--assets must be at least 2 and --samples at least 2000")
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

    import copy

    from distributed import Client, LocalCluster

    import adaptobs
    from adaptobs import fleet

    cxx = cxx_loop(root, 100_000)
    cases = {
        "Guyader-Zhang satellite": ("GuyaderZhangObserver", *satellite_fleet(args.assets, args.samples)),
        "Dey-Bhasin MIMO": ("DeyBhasinObserver", *dey_bhasin_fleet(max(2, args.assets // 4), args.samples)),
    }
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for label, (cxx_name, config, frame) in cases.items():
            total = len(frame)
            U, Y, Psi = one_asset(config, frame)

            def run_only():
                copy.deepcopy(config.observer).run(U, Y, Psi)

            def run_and_monitor():
                result = copy.deepcopy(config.observer).run(U, Y, Psi)
                status = result.status.astype(np.int64)
                status[:config.monitor_from] = 1
                adaptobs.FaultMonitor(config.design).run(result.parameters, result.output_error, status=status)

            # Measured round-robin, so that the machine's load moves every figure of a row alike.
            work = {"run() (observer)": (len(Y), run_only),
                    "run() + FaultMonitor.run()": (len(Y), run_and_monitor),
                    "fleet, serial": (total, lambda: fleet.process(frame, config))}
            for every in (1000, 10_000):
                def checkpointed(every=every):
                    directory = tempfile.mkdtemp(dir=scratch)
                    fleet.process(frame, config, checkpoint_dir=directory, every=every)

                work[f"fleet, serial, checkpoints every {every}"] = (total, checkpointed)
            files = []
            assets = np.sort(frame["asset_id"].unique())
            for i, group in enumerate(np.array_split(assets, 8)):
                path = os.path.join(scratch, f"{cxx_name}-{i}.parquet")
                frame[frame["asset_id"].isin(group)].to_parquet(path)
                files.append(path)
            with contextlib.ExitStack() as stack:
                for workers in (1, 2):
                    cluster = stack.enter_context(LocalCluster(
                        n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                        dashboard_address=":0", memory_limit=0, silence_logs=40))
                    client = stack.enter_context(Client(cluster))
                    client.wait_for_workers(workers, timeout=60)
                    fleet.process(files[:workers], config, client=client)  # warm: imports on the workers
                    work[f"fleet, {workers} worker{'s' * (workers > 1)}"] = (
                        total, lambda client=client: fleet.process(files, config, client=client))
                best = {name: float("inf") for name in work}
                for _ in range(args.repetitions):
                    for name, (_, function) in work.items():
                        clock = time.perf_counter if "worker" in name else time.process_time
                        best[name] = min(best[name], best_of(1, function, clock))
            figures = {"C++ loop (observer)": 1e9 / cxx[cxx_name]}
            figures.update({name: work[name][0] / best[name] for name in work})
            rows.append((label, total, figures))

    for label, total, figures in rows:
        print(f"{label}: {args.assets if 'satellite' in label else max(2, args.assets // 4)} assets, "
              f"{total} asset-samples")
        base = figures["run() + FaultMonitor.run()"]
        for name, rate in figures.items():
            print(f"  {name:<44}{rate / 1e6:>9.3f} M asset-samples/s{rate / base:>8.2f} x run() + monitor")
        serial = figures["fleet, serial"]
        for every in (1000, 10_000):
            overhead = serial / figures[f"fleet, serial, checkpoints every {every}"] - 1
            print(f"  checkpoint overhead at K = {every}: {100 * overhead:+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
