"""A constellation of N satellites of Guyader & Zhang (2003), each watched by its own Guyader-Zhang
observer and FaultMonitor on a Dask LocalCluster (adaptobs.fleet): a bias of 0.05 on the first output
sensor appears in some satellites at random times. The telemetry is written to Parquet, processed on W
worker processes with checkpoints (with --kill-one, one worker is killed mid-run), and the detections
are scored against the injected truth; the distributed result is compared with a serial run.

    python python/examples/fleet.py [--assets 40] [--samples 6000] [--workers 2] [--kill-one]
                                    [--out fleet_python.png] [--no-figure]

Prints `name = value` lines: detection_rate, mean_detection_delay (s), false_alarms_per_asset_hour,
assets_processed, equal_to_serial (1 when the distributed alarms and estimates equal the serial run's
bit for bit).
"""

import argparse
import os
import signal
import tempfile
import threading
import time

import numpy as np

import adaptobs
from adaptobs import fleet

MONITOR_FROM = 1000  # samples (100 s): the estimates have converged
BIAS = 0.05


def observer(s):
    model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
    return adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"])


def configuration(s):
    """A FaultMonitor designed from 8 fault-free runs of 1200 s (false alarms once an hour per test)."""
    parameters, errors = [], []
    for seed in range(1, 9):
        data = adaptobs.examples.simulate_satellite(12000, seed=seed)
        result = observer(s).run(data["U"], data["Y"], data["Psi"])
        parameters.append(result.parameters[MONITOR_FROM:])
        errors.append(result.output_error[MONITOR_FROM:])
    design = adaptobs.design_fault_monitor(parameters, errors, s["theta"], drift=1.0,
                                           mean_samples_between_false_alarms=36000.0, stride=100, window=100)
    return fleet.AssetConfig(observer(s), design, monitor_from=MONITOR_FROM)


def telemetry(assets, samples, rng):
    """The constellation's telemetry and the sample of each satellite's fault (-1: none): a third of
    them, at times drawn uniformly over the monitored part of the run."""
    import pandas as pd

    faults = np.full(assets, -1)
    faulty = rng.choice(assets, size=max(1, assets // 3), replace=False)
    faults[faulty] = rng.integers(MONITOR_FROM + 500, samples - 500, size=faulty.size)
    frames = []
    for asset in range(assets):
        data = adaptobs.examples.simulate_satellite(samples, seed=1000 + asset)
        Y = data["Y"].copy()
        if faults[asset] >= 0:
            Y[faults[asset]:, 0] += BIAS
        columns = {"asset_id": np.full(samples, asset), "t": np.arange(samples) * 0.1}
        columns.update({f"u_{i}": data["U"][:, i] for i in range(2)})
        columns.update({f"y_{i}": Y[:, i] for i in range(2)})
        columns.update({f"psi_{i}_{j}": data["Psi"][:, i, j] for i in range(4) for j in range(2)})
        frames.append(pd.DataFrame(columns))
    return pd.concat(frames, ignore_index=True), faults


def run_on_cluster(files, config, workers, checkpoints, kill_one):
    """fleet.process on a LocalCluster of `workers` processes; with kill_one, the pid of a busy worker is
    sent SIGKILL once two assets have checkpoints, and its nanny starts another."""
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=":0", memory_limit=0, silence_logs=50) as cluster, Client(cluster) as client:
        client.wait_for_workers(workers, timeout=60)
        if not kill_one:
            return fleet.process(files, config, client=client, checkpoint_dir=checkpoints, every=1000), 0
        pids = client.run(os.getpid)
        done = {}

        def run():
            try:
                done["result"] = fleet.process(files, config, client=client, checkpoint_dir=checkpoints, every=500)
            except BaseException as error:  # noqa: BLE001  (raised below)
                done["error"] = error

        thread = threading.Thread(target=run, daemon=True)
        thread.start()
        deadline = time.monotonic() + 120
        killed = 0
        while time.monotonic() < deadline and thread.is_alive():
            busy = [a for a, tasks in client.processing().items() if tasks]
            if busy and len([f for f in os.listdir(checkpoints) if f.endswith(".ckpt")]) >= 2:
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed = 1
                break
            time.sleep(0.01)
        thread.join(timeout=600)
        if "error" in done:
            raise done["error"]
        return done["result"], killed


def score(result, faults, samples, Ts):
    """Detection rate, mean delay (s) and false alarms per asset-hour of monitored time."""
    alarms = result.alarms
    delays, false_alarms = [], 0
    for asset, fault in enumerate(faults):
        times = np.sort(alarms.loc[alarms["asset_id"] == asset, "sample"].to_numpy())
        if fault < 0:
            false_alarms += times.size
            continue
        false_alarms += int(np.count_nonzero(times < fault))
        after = times[times >= fault]
        if after.size:
            delays.append((after[0] - fault) * Ts)
    faulty = int(np.count_nonzero(faults >= 0))
    monitored_hours = sum(((samples if f < 0 else f) - MONITOR_FROM) for f in faults) * Ts / 3600
    return (len(delays) / faulty, float(np.mean(delays)) if delays else float("nan"), false_alarms / monitored_hours)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--assets", type=int, default=40)
    parser.add_argument("--samples", type=int, default=6000)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--kill-one", action="store_true", help="kill one worker process mid-run")
    parser.add_argument("--seed", type=int, default=53)
    parser.add_argument("--out", default="fleet_python.png")
    parser.add_argument("--no-figure", action="store_true", help="print the figures of merit only")
    args = parser.parse_args()
    if not 3 <= args.assets <= 100_000:
        parser.error("--assets must lie in [3, 1e5]")
    if not 3000 <= args.samples <= 10**7:
        parser.error("--samples must lie in [3000, 1e7]: the monitor starts at sample 1000, faults from 1500")
    if not 1 <= args.workers <= 64:
        parser.error("--workers must lie in [1, 64]")
    if args.kill_one and args.workers < 2:
        parser.error("--kill-one needs at least 2 workers")

    s = adaptobs.examples.satellite()
    config = configuration(s)
    frame, faults = telemetry(args.assets, args.samples, np.random.default_rng(args.seed))
    with tempfile.TemporaryDirectory() as scratch:
        files = []
        for i, group in enumerate(np.array_split(np.arange(args.assets), max(2, 2 * args.workers))):
            path = os.path.join(scratch, f"telemetry-{i}.parquet")
            frame[frame["asset_id"].isin(group)].to_parquet(path)
            files.append(path)
        checkpoints = os.path.join(scratch, "checkpoints")
        result, killed = run_on_cluster(files, config, args.workers, checkpoints, args.kill_one)
    serial = fleet.process(frame, config)
    equal = int(result.alarms.equals(serial.alarms) and result.assets.equals(serial.assets))
    rate, delay, false_rate = score(result, faults, args.samples, s["Ts"])
    print(f"detection_rate = {rate:.4g}")
    print(f"mean_detection_delay = {delay:.4g}")
    print(f"false_alarms_per_asset_hour = {false_rate:.4g}")
    print(f"assets_processed = {len(result.assets)}")
    print(f"workers_killed = {killed}")
    print(f"equal_to_serial = {equal}")
    if args.no_figure:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(10, max(3, 0.15 * args.assets)))
    markers = {"cusum": "o", "glr": "s", "chi_square": "^"}
    for detector, marker in markers.items():
        rows = result.alarms[result.alarms["detector"] == detector]
        ax.plot(rows["t"], rows["asset_id"], marker, ms=4, ls="none", label=f"{detector} alarm")
    faulty = np.flatnonzero(faults >= 0)
    ax.plot(faults[faulty] * s["Ts"], faulty, "k|", ms=12, mew=2, label="true fault")
    ax.axvline(MONITOR_FROM * s["Ts"], color="0.6", ls=":", label="monitor starts")
    ax.set_xlim(0, args.samples * s["Ts"])
    ax.set_xlabel("t (s)")
    ax.set_ylabel("satellite")
    ax.set_title(f"Alarms of {args.assets} satellites on {args.workers} Dask worker{'s' if args.workers > 1 else ''}"
                 + (" (one killed mid-run)" if killed else ""))
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=90)
    print("figure:", args.out)


if __name__ == "__main__":
    main()
