"""adaptobs.fleet: one Guyader-Zhang observer and FaultMonitor per satellite of a fleet, serially and on a
LocalCluster of two worker processes on loopback, with checkpoints, a worker killed mid-run, corrupted
checkpoints and the distributed Monte Carlo."""

import copy
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import adaptobs

pd = pytest.importorskip("pandas")
pytest.importorskip("pyarrow")
distributed = pytest.importorskip("distributed")

from adaptobs import fleet  # noqa: E402

MONITOR_FROM = 1000  # samples: the estimates have converged (python/examples/satellite_fault.py)
SAMPLES = 3000
ASSETS = 24
FAULTY = (3, 10, 17)  # assets whose first output sensor gains a bias at FAULT_AT
FAULT_AT = 2000


def make_observer(s):
    model = adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"], np=2)
    return adaptobs.GuyaderZhangObserver(model, s["K"], s["mu"], s["x0_estimate"], s["theta0_estimate"])


@pytest.fixture(scope="module")
def config():
    """A fleet-wide configuration: the satellite's observer and a monitor designed from 8 fault-free runs."""
    s = adaptobs.examples.satellite()
    parameters, errors = [], []
    for seed in range(1, 9):
        data = adaptobs.examples.simulate_satellite(12000, seed=seed)
        result = make_observer(s).run(data["U"], data["Y"], data["Psi"])
        parameters.append(result.parameters[MONITOR_FROM:])
        errors.append(result.output_error[MONITOR_FROM:])
    design = adaptobs.design_fault_monitor(parameters, errors, s["theta"], drift=1.0,
                                           mean_samples_between_false_alarms=36000.0, stride=100, window=100)
    return fleet.AssetConfig(make_observer(s), design, monitor_from=MONITOR_FROM)


def telemetry(assets, samples):
    """The satellite's telemetry for `assets` satellites (seed 100 + asset), the FAULTY ones with a bias
    of 0.05 on output 0 from FAULT_AT on; rows in no particular order across assets."""
    frames = []
    for asset in range(assets):
        data = adaptobs.examples.simulate_satellite(samples, seed=100 + asset)
        Y = data["Y"].copy()
        if asset in FAULTY:
            Y[FAULT_AT:, 0] += 0.05
        columns = {"asset_id": np.full(samples, asset), "t": np.arange(samples) * 0.1}
        columns.update({f"u_{i}": data["U"][:, i] for i in range(data["U"].shape[1])})
        columns.update({f"y_{i}": Y[:, i] for i in range(Y.shape[1])})
        Psi = data["Psi"]
        columns.update({f"psi_{i}_{j}": Psi[:, i, j] for i in range(Psi.shape[1]) for j in range(Psi.shape[2])})
        frames.append(pd.DataFrame(columns))
    return pd.concat(frames, ignore_index=True)


@pytest.fixture(scope="module")
def fleet_data():
    return telemetry(ASSETS, SAMPLES)


def serial_loop(frame, config):
    """The reference: for each asset, one run() of a copy of the observer over all its samples and one
    FaultMonitor.run(), written without adaptobs.fleet."""
    t_all = frame["t"].to_numpy()
    U_all, Y_all = frame[["u_0", "u_1"]].to_numpy(), frame[["y_0", "y_1"]].to_numpy()
    Psi_all = frame[[f"psi_{i}_{j}" for i in range(4) for j in range(2)]].to_numpy().reshape(-1, 4, 2)
    alarms, finals = [], []
    for asset, rows in sorted(frame.groupby("asset_id").indices.items()):
        rows = rows[np.argsort(t_all[rows], kind="stable")]
        observer = copy.deepcopy(config.observer)
        result = observer.run(U_all[rows], Y_all[rows], Psi_all[rows])
        status = result.status.astype(np.int64)
        status[:config.monitor_from] = int(adaptobs.UpdateStatus.nonfinite_input)
        out = adaptobs.FaultMonitor(config.design).run(result.parameters, result.output_error, status=status)
        t = t_all[rows]
        for code, name in enumerate(fleet.DETECTORS):
            for k in np.flatnonzero(out[f"{name}_alarm"]):
                alarms.append((asset, k, t[k], code, out[fleet.ALARM_STATISTIC[name]][k]))
        finals.append((asset, observer.parameters, observer.state, observer.step))
    alarms.sort(key=lambda a: (a[0], a[1], a[3]))
    return alarms, finals


def assert_equals_serial(result, reference):
    alarms, finals = reference
    table = result.alarms
    assert len(table) == len(alarms)
    assert np.array_equal(table["asset_id"].to_numpy(), [a[0] for a in alarms])
    assert np.array_equal(table["sample"].to_numpy(), [a[1] for a in alarms])
    assert np.array_equal(table["t"].to_numpy(), [a[2] for a in alarms])
    assert np.array_equal(table["detector"].cat.codes.to_numpy(), [a[3] for a in alarms])
    assert np.array_equal(table["statistic"].to_numpy(), [a[4] for a in alarms])
    assets = result.assets
    assert np.array_equal(assets["asset_id"].to_numpy(), [f[0] for f in finals])
    assert np.array_equal(assets[["theta_0", "theta_1"]].to_numpy(), np.array([f[1] for f in finals]))
    assert np.array_equal(assets[[f"x_{i}" for i in range(4)]].to_numpy(), np.array([f[2] for f in finals]))
    assert np.array_equal(assets["steps"].to_numpy(), [f[3] for f in finals])


def assert_same(a, b):
    pd.testing.assert_frame_equal(a.alarms, b.alarms, check_exact=True)
    pd.testing.assert_frame_equal(a.assets, b.assets, check_exact=True)


@pytest.fixture(scope="module")
def reference(fleet_data, config):
    return serial_loop(fleet_data, config)


@pytest.fixture(scope="module")
def cluster():
    """Two worker processes of one thread on loopback; started and stopped within the module, with
    bounded waits."""
    from distributed import Client, LocalCluster

    local = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                         dashboard_address=":0", memory_limit=0, silence_logs=40)
    client = Client(local, timeout=30)
    try:
        client.wait_for_workers(2, timeout=30)
        yield client
    finally:
        client.close(timeout=10)
        local.close(timeout=10)
    assert local.status.name == "closed"


def test_the_serial_fleet_equals_a_loop_over_the_assets_and_finds_the_faults(fleet_data, config, reference):
    result = fleet.process(fleet_data, config)
    assert_equals_serial(result, reference)
    # Each biased satellite raises an alarm within 150 samples of the fault; the fault-free ones (21 x 2000
    # monitored samples, three tests designed for one false alarm in 36000 samples each) raise at most 4.
    alarms = result.alarms
    first = alarms[alarms["sample"] >= FAULT_AT].groupby("asset_id")["sample"].min()
    assert all(FAULT_AT <= first[a] < FAULT_AT + 150 for a in FAULTY)
    assert np.count_nonzero(~alarms["asset_id"].isin(FAULTY)) <= 4
    # Each alarm is reported with its statistic above its test's threshold.
    threshold = {"cusum": config.design.cusum.threshold, "glr": config.design.glr_threshold,
                 "chi_square": adaptobs.FaultMonitor(config.design).chi_square.threshold}
    assert all(row.statistic > threshold[row.detector] for row in alarms.itertuples())
    assert (result.assets["health"] == "healthy").all()
    assert np.array_equal(result.assets["samples"], np.full(ASSETS, SAMPLES))


def test_the_distributed_fleet_equals_the_serial_loop(fleet_data, config, reference, cluster, tmp_path):
    # A pandas DataFrame cut into partitions of whole assets, and Parquet files, one per group of assets.
    assert_equals_serial(fleet.process(fleet_data, config, client=cluster, timeout=60), reference)
    files = []
    for i, group in enumerate(np.array_split(np.arange(ASSETS), 3)):
        path = tmp_path / f"part-{i}.parquet"
        fleet_data[fleet_data["asset_id"].isin(group)].to_parquet(path)
        files.append(str(path))
    assert_equals_serial(fleet.process(files, config, client=cluster, timeout=60), reference)
    # A Dask DataFrame indexed by asset: its partitions hold whole assets.
    import dask.dataframe as dd

    frame = dd.from_pandas(fleet_data.set_index("asset_id").sort_index(), npartitions=5, sort=True)
    assert frame.npartitions > 1
    assert_equals_serial(fleet.process(frame, config, client=cluster, timeout=60), reference)


def test_a_thousand_assets_on_two_workers_equal_the_serial_loop(config, cluster, tmp_path):
    """A fleet of 1000 assets with 10^3 samples each, from 4 Parquet files on the two workers, monitored
    from sample 500. With ADAPTOBS_FLEET_SAMPLES=10000 in the environment, 10^4 samples each: 1.1 GB of
    telemetry, which takes the time of the whole Python suite again (docs/fleet.md)."""
    assets, samples = 1000, int(os.environ.get("ADAPTOBS_FLEET_SAMPLES", "1000"))
    columns = {name: [] for name in ("asset_id", "t", "u_0", "u_1", "y_0", "y_1")}
    columns.update({f"psi_{i}_{j}": [] for i in range(4) for j in range(2)})
    for asset in range(assets):
        data = adaptobs.examples.simulate_satellite(samples, seed=5000 + asset)
        columns["asset_id"].append(np.full(samples, asset))
        columns["t"].append(np.arange(samples) * 0.1)
        for i in range(2):
            columns[f"u_{i}"].append(data["U"][:, i])
            bias = 0.1 * (np.arange(samples) >= 700) if asset % 97 == 0 and i == 0 else 0.0
            columns[f"y_{i}"].append(data["Y"][:, i] + bias)
        for i in range(4):
            for j in range(2):
                columns[f"psi_{i}_{j}"].append(data["Psi"][:, i, j])
    frame = pd.DataFrame({name: np.concatenate(parts) for name, parts in columns.items()})
    early = copy.copy(config)
    early.monitor_from = 500
    files = []
    for i, group in enumerate(np.array_split(np.arange(assets), 4)):
        path = tmp_path / f"part-{i}.parquet"
        frame[frame["asset_id"].isin(group)].to_parquet(path)
        files.append(str(path))
    result = fleet.process(files, early, client=cluster, timeout=120 * samples / 1000)
    reference = serial_loop(frame, early)
    assert len(result.assets) == assets
    assert_equals_serial(result, reference)
    # The 11 assets with a bias of 0.1 on output 0 from sample 700 raise alarms. The 989 others have
    # 989 (samples - 500) monitored samples (489,000 for 10^3 samples each) and three tests designed
    # for one false alarm in 36,000 samples each: about 41 false alarms, on at most as many assets.
    alarmed = set(result.alarms["asset_id"])
    assert set(range(0, assets, 97)) <= alarmed
    assert len(alarmed) - 11 <= 1.5 * 3 * 989 * (samples - 500) / 36000


def test_a_regressor_given_once_serves_every_sample(fleet_data, config):
    # Telemetry without psi columns, one regressor for all samples in the configuration: each asset's
    # estimates are those of run() with that one nx x np regressor.
    few = fleet_data[fleet_data["asset_id"] < 3].drop(columns=[c for c in fleet_data if c.startswith("psi_")])
    Psi = adaptobs.examples.simulate_satellite(2)["Psi"][0] * 1.5
    constant = fleet.AssetConfig(config.observer, config.design, monitor_from=MONITOR_FROM, regressor=Psi)
    result = fleet.process(few, constant, every=700)
    for asset in range(3):
        rows = few[few["asset_id"] == asset]
        expected = copy.deepcopy(config.observer).run(rows[["u_0", "u_1"]].to_numpy(), rows[["y_0", "y_1"]].to_numpy(),
                                                      Psi)
        assert np.array_equal(result.assets.loc[asset, ["theta_0", "theta_1"]].to_numpy(dtype=float),
                              expected.parameters[-1])
    with pytest.raises(adaptobs.ConfigurationError, match="no column 'psi_0_0'"):
        fleet.process(few, config)


def test_a_nan_output_is_a_channel_not_measured(fleet_data, config):
    # Asset 1 loses its first output for 10 s from t = 150 s (NaN in y_0), asset 2 both for 5 s from
    # t = 220 s. Each sample is a masked update, equal to run() with `present`, not a refused sample;
    # the monitor passes those samples over and raises no alarm on them.
    few = fleet_data[fleet_data["asset_id"] < 3].copy()
    one = (few["asset_id"] == 1) & (few["t"] >= 150.0) & (few["t"] < 160.0)
    both = (few["asset_id"] == 2) & (few["t"] >= 220.0) & (few["t"] < 225.0)
    few.loc[one, "y_0"] = np.nan
    few.loc[both, ["y_0", "y_1"]] = np.nan
    result = fleet.process(few, config, every=1000)
    assert np.array_equal(result.assets["steps"], np.full(3, SAMPLES))
    Psi = few[[f"psi_{i}_{j}" for i in range(4) for j in range(2)]].to_numpy().reshape(-1, 4, 2)
    for asset in range(3):
        rows = (few["asset_id"] == asset).to_numpy()
        Y = few.loc[rows, ["y_0", "y_1"]].to_numpy()
        present = ~np.isnan(Y)
        observer = copy.deepcopy(config.observer)
        observer.run(few.loc[rows, ["u_0", "u_1"]].to_numpy(), np.where(present, Y, 0.0), Psi[rows], present=present)
        assert np.array_equal(result.assets.loc[asset, ["theta_0", "theta_1"]].to_numpy(dtype=float),
                              observer.parameters)
    gaps = set(zip(few.loc[one | both, "asset_id"], few.loc[one | both, "t"]))
    assert not any(alarm in gaps for alarm in zip(result.alarms["asset_id"], result.alarms["t"]))


def test_a_run_with_checkpoints_resumes_from_them(fleet_data, config, tmp_path):
    # Interrupted after the first 1700 samples of each asset, then given all of them: equal to one run.
    uninterrupted = fleet.process(fleet_data, config)
    first = fleet_data[fleet_data["t"] < 170.0 - 1e-9]
    fleet.process(first, config, checkpoint_dir=str(tmp_path), every=500)
    resumed = fleet.process(fleet_data, config, checkpoint_dir=str(tmp_path), every=500)
    assert_same(resumed, uninterrupted)
    # A finished asset's checkpoint holds its final state: a rerun reads it and does no work.
    again = fleet.process(fleet_data, config, checkpoint_dir=str(tmp_path), every=500)
    assert_same(again, uninterrupted)


@pytest.mark.parametrize("damage", ["truncated", "flipped", "flipped in the header"])
def test_a_damaged_checkpoint_is_refused_naming_the_asset_and_the_file(fleet_data, config, tmp_path, damage):
    few = fleet_data[fleet_data["asset_id"] < 2]
    fleet.process(few, config, checkpoint_dir=str(tmp_path), every=1000)
    path = tmp_path / "asset-1.ckpt"
    data = bytearray(path.read_bytes())
    why = {"truncated": "truncated", "flipped": "SHA-256", "flipped in the header": "SHA-256"}[damage]
    if damage == "truncated":
        data = data[:len(data) - 37]
    elif damage == "flipped":
        data[len(data) - 100] ^= 0x10  # in the arrays
    else:
        at = data.index(b'"position": ') + len(b'"position": ')
        data[at] ^= 0x01  # the sample the asset would resume from: 1000 -> 0000, still valid JSON
    path.write_bytes(bytes(data))
    with pytest.raises(fleet.CheckpointError, match=rf"asset 1 in file '.*asset-1\.ckpt'.*{why}"):
        fleet.process(few, config, checkpoint_dir=str(tmp_path), every=1000)


def test_a_checkpoint_of_another_snapshot_version_is_refused(fleet_data, config, tmp_path):
    few = fleet_data[fleet_data["asset_id"] == 0]
    fleet.process(few, config, checkpoint_dir=str(tmp_path), every=1000)
    path = tmp_path / "asset-0.ckpt"
    data = path.read_bytes()
    end = data.index(b"\n", len(fleet.CHECKPOINT_MAGIC))
    header = json.loads(data[len(fleet.CHECKPOINT_MAGIC):end])
    # A sound checkpoint (its checksum right) holding a snapshot of a later version of the observer.
    header["observer"][1] += 1
    header["sha256"] = fleet._digest(header, data[end + 1:])
    path.write_bytes(fleet.CHECKPOINT_MAGIC + json.dumps(header).encode() + data[end:])
    with pytest.raises(fleet.CheckpointError, match=r"asset 0 in file '.*asset-0\.ckpt'.*observer snapshot"):
        fleet.process(few, config, checkpoint_dir=str(tmp_path), every=1000)


def test_bad_configuration_fails_before_any_work_naming_the_column(fleet_data, config, tmp_path):
    few = fleet_data[fleet_data["asset_id"] < 2]
    ckpt = tmp_path / "none"

    def refused(match, telemetry=few, **arguments):
        with pytest.raises(adaptobs.ConfigurationError, match=match):
            fleet.process(telemetry, arguments.pop("configuration", config),
                          checkpoint_dir=str(ckpt / "x"), **arguments)
        assert not (ckpt / "x").exists() or not any((ckpt / "x").iterdir())

    refused(r"'asset_column' names column 'satellite'", asset_column="satellite")
    refused(r"no column 'psi_3_1'", few.drop(columns="psi_3_1"))
    refused(r"no column 'y_1'", few.drop(columns="y_1"))
    # Per-asset configurations of different shapes: the satellite measuring its first output only, and
    # the Dey-Bhasin MIMO observer (2 inputs, 2 outputs, no regressor).
    s = adaptobs.examples.satellite()
    one_output = adaptobs.GuyaderZhangObserver(adaptobs.DiscreteLtiModel(s["A"], s["B"], s["C"][:1], np=2),
                                               s["K"][:, :1], s["mu"], s["x0_estimate"], s["theta0_estimate"])
    m = adaptobs.examples.dey_bhasin_mimo()
    dey_bhasin = adaptobs.DeyBhasinObserver(m["f"], m["x0_estimate"], m["a0_estimate"], m["B0_estimate"],
                                            k0=m["k0"], kmin=m["kmin"], R=m["R"])
    for observer, column in ((one_output, "y_1"), (dey_bhasin, "psi_0_0")):
        with pytest.raises(adaptobs.ConfigurationError, match="argument 'design'"):
            fleet.AssetConfig(observer, config.design)
        mismatched = copy.copy(config)
        mismatched.observer = observer  # past AssetConfig's own check of the design
        refused(rf"shapes differ.*column '{column}' is read by some assets and not by others",
                configuration={0: config, 1: mismatched})
    refused(r"column 'asset_id' holds assets without a configuration.*\[1\]", configuration={0: config})
    refused(r"column 'u_7' is read by no observer", few.assign(u_7=0.0))


def test_killing_a_worker_mid_run_loses_and_duplicates_nothing(fleet_data, config, reference, cluster, tmp_path):
    """One of the two worker processes is killed by its pid once checkpoints exist; its nanny starts
    another, the scheduler reruns the lost tasks, and their assets resume from their checkpoints."""
    pids = cluster.run(os.getpid)
    assert len(pids) == 2
    done = {}

    def run():
        try:
            done["result"] = fleet.process(fleet_data, config, client=cluster, checkpoint_dir=str(tmp_path),
                                           every=250, partitions=4, timeout=90)
        except BaseException as error:  # noqa: BLE001  (reported by the test thread)
            done["error"] = error

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and len(list(tmp_path.glob("asset-*.ckpt"))) < 2:
        time.sleep(0.01)
    assert len(list(tmp_path.glob("asset-*.ckpt"))) >= 2, "no checkpoint written within 60 s"
    finished_before = sum(1 for p in tmp_path.glob("asset-*.ckpt") if _position(p) == SAMPLES)
    busy = [address for address, tasks in cluster.processing().items() if tasks]
    assert busy, "no worker was processing a task"
    victim = pids[busy[0]]
    os.kill(victim, signal.SIGKILL)
    worker.join(timeout=120)
    assert not worker.is_alive(), "the run did not finish within 120 s of the kill"
    if "error" in done:
        raise done["error"]
    assert finished_before < ASSETS  # the kill came mid-run
    assert victim not in cluster.run(os.getpid).values()  # a new worker process replaced the killed one
    assert_equals_serial(done["result"], reference)


def _position(path):
    data = path.read_bytes()
    end = data.index(b"\n", len(fleet.CHECKPOINT_MAGIC))
    return json.loads(data[len(fleet.CHECKPOINT_MAGIC):end])["position"]


class Scenario:
    """The satellite with noise seeded by `seed` and, when `faulty`, a bias of 0.05 on output 0 from
    sample 2000; the alarms of the fleet's FaultMonitor from MONITOR_FROM on (times in samples)."""

    def __init__(self, design):
        self.design = design

    def __call__(self, seed, faulty):
        s = adaptobs.examples.satellite()
        data = adaptobs.examples.simulate_satellite(2500, seed=seed)
        Y = data["Y"].copy()
        if faulty:
            Y[2000:, 0] += 0.05
        result = make_observer(s).run(data["U"], Y, data["Psi"])
        status = result.status.astype(np.int64)
        status[:MONITOR_FROM] = int(adaptobs.UpdateStatus.nonfinite_input)
        out = adaptobs.FaultMonitor(self.design).run(result.parameters, result.output_error, status=status)
        raised = out["cusum_alarm"] | out["glr_alarm"] | out["chi_square_alarm"]
        return (float(MONITOR_FROM), 2500.0, np.flatnonzero(raised).astype(float))


def test_the_distributed_monte_carlo_equals_the_single_process_evaluator(cluster, config):
    fault = adaptobs.FaultDescription(2000.0)
    scenario = Scenario(config.design)
    single = adaptobs.evaluate_detection(scenario, fault, 24, first_seed=7, threads=1)
    spread = fleet.evaluate_detection(cluster, scenario, fault, 24, first_seed=7, block=5)
    # The bias is found in most runs, within a few chi-square windows; false alarms are rare.
    assert single.detection_rate >= 0.75 and single.mean_detection_delay < 300 and single.false_alarms <= 3
    for name in ("seeds", "detection_rate", "mean_detection_delay", "p95_detection_delay",
                 "quiet_before_fault_rate", "false_alarms", "fault_free_time", "false_alarm_rate"):
        assert getattr(spread, name) == getattr(single, name), name
    assert np.array_equal(spread.delays, single.delays)
    assert fleet.map_seeds(None, int, 7, first_seed=3, block=2) == [3, 4, 5, 6, 7, 8, 9]
