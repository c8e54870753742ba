"""Fleets: one observer and one FaultMonitor per asset, over partitions of telemetry, on one process
or on a ``dask.distributed`` cluster, with checkpoints from which a lost worker's assets resume.

Telemetry is a table with one row per sample: an asset column (``asset_id``), the time ``t``, the
inputs ``u_0 ... u_{nu-1}``, the outputs ``y_0 ... y_{ny-1}`` and, for observers whose samples carry
a regressor (Guyader-Zhang, Guiro, the augmented Kalman filter), ``psi_{i}_{j}`` (row i, column j of
the nx x np regressor), unless the configuration gives one regressor for every sample. It comes as a
pandas DataFrame, a Dask DataFrame (each partition holding whole assets) or Parquet files (each file
holding whole assets). Each asset's samples are processed in time order by the batch API: the
observer's ``run()`` and the monitor's ``run()``, both in C++ with the GIL released.

Every result is a pure function of the data and the configuration: the observers and monitors are
deterministic, a run in chunks equals one run (``run()`` equals a loop of ``update()``), and a
restored snapshot continues bit for bit. So the alarms and final estimates do not depend on the
partitioning, the number of workers, or on a worker lost and replaced mid-run.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import json
import os
import re
from typing import Any, Callable, Mapping, Optional, Sequence

import numpy as np

from . import _core

__all__ = [
    "AssetConfig",
    "CheckpointError",
    "FleetResult",
    "TelemetryLayout",
    "evaluate_detection",
    "map_seeds",
    "process",
    "process_partition",
]

ConfigurationError = _core.ConfigurationError

# The three tests of a FaultMonitor, and the FaultMonitor.run column of the statistic each alarm is
# reported with (the running statistics are cleared by the alarm itself).
DETECTORS = ("cusum", "glr", "chi_square")
ALARM_STATISTIC = {"cusum": "cusum_alarm_statistic", "glr": "glr_alarm_statistic",
                   "chi_square": "chi_square_decision_statistic"}

CHECKPOINT_MAGIC = b"ADAPTOBS-FLEET-CHECKPOINT\n"
CHECKPOINT_FORMAT = 1


class CheckpointError(RuntimeError):
    """A checkpoint that cannot be trusted (truncated, corrupted, of another asset, format or
    snapshot version, or of observers or monitors of other sizes or settings): refused, naming
    the asset and the file."""


@dataclasses.dataclass
class AssetConfig:
    """What one asset runs: an observer (a template, copied for each asset: its model, gains and
    initial estimates), the FaultMonitorDesign of its monitor, the sample from which the monitor
    watches the estimates (before it, the estimates converge and every sample is passed over), and,
    for observers whose regressor does not vary, the one nx x np regressor of every sample."""

    observer: Any
    design: Any
    monitor_from: int = 0
    regressor: Optional[np.ndarray] = None

    def __post_init__(self):
        if not hasattr(self.observer, "run") or not hasattr(self.observer, "snapshot"):
            raise ConfigurationError("AssetConfig: argument 'observer' must be an adaptobs discrete-time observer")
        if not isinstance(self.design, _core.FaultMonitorDesign):
            raise ConfigurationError("AssetConfig: argument 'design' must be an adaptobs.FaultMonitorDesign")
        if int(self.monitor_from) != self.monitor_from or self.monitor_from < 0:
            raise ConfigurationError("AssetConfig: argument 'monitor_from' must be a non-negative integer")
        self.monitor_from = int(self.monitor_from)
        if self.regressor is not None:
            self.regressor = np.array(self.regressor, dtype=np.float64)
            nx, _, _, np_ = self.observer.sizes
            if self.regressor.shape != (nx, np_):
                raise ConfigurationError(f"AssetConfig: argument 'regressor' must be {nx}x{np_} "
                                         f"(got {self.regressor.shape})")
        nx, nu, ny, np_ = self.observer.sizes
        monitor = _core.FaultMonitor(self.design)
        if monitor.cusum.nominal.size != np_:
            raise ConfigurationError(f"AssetConfig: argument 'design' watches {monitor.cusum.nominal.size} "
                                     f"parameters, the observer has {np_}")
        outputs = np.asarray(self.design.output_error_covariance).shape[0]
        if outputs != ny:
            raise ConfigurationError(f"AssetConfig: argument 'design' tests {outputs} output "
                                     f"errors, the observer has {ny} outputs")

    @property
    def takes_regressor(self) -> bool:
        return _takes_regressor(self.observer)


def _takes_regressor(observer) -> bool:
    """Whether the observer's samples carry a regressor: a run over no samples with one is refused
    by those whose samples have none (Dey-Bhasin, Suzuki), and no observer state changes."""
    nx, nu, ny, np_ = observer.sizes
    probe = copy.deepcopy(observer)
    try:
        probe.run(np.zeros((0, nu)), np.zeros((0, ny)), np.zeros((0, nx, np_)))
    except ConfigurationError as error:
        if "must be None" in str(error):
            return False
        raise
    return True


@dataclasses.dataclass(frozen=True)
class TelemetryLayout:
    """The columns of a telemetry table: the asset and time columns, and the inputs, outputs and
    regressor entries the observers read (regressor empty when the configuration gives it)."""

    asset: str
    time: str
    inputs: tuple
    outputs: tuple
    regressor: tuple
    sizes: tuple

    @property
    def columns(self) -> list:
        return [self.asset, self.time, *self.inputs, *self.outputs, *self.regressor]


def _layout(columns: Sequence[str], configs: Mapping, default: Optional[AssetConfig], asset_column: str,
            time_column: str) -> TelemetryLayout:
    """The layout every configuration reads from `columns`, or ConfigurationError naming the column
    that is unknown, missing or read by some assets and not by others."""
    columns = [str(c) for c in columns]
    present = set(columns)
    for role, name in (("asset_column", asset_column), ("time_column", time_column)):
        if name not in present:
            raise ConfigurationError(f"fleet: argument '{role}' names column '{name}', which the telemetry does "
                                     f"not have (columns: {', '.join(columns)})")
    named = ([("default", default)] if default is not None else []) + [(f"asset {a!r}", c) for a, c in configs.items()]
    if not named:
        raise ConfigurationError("fleet: argument 'config' must give an AssetConfig (fleet-wide) or a dict of them")
    first_name, first = named[0]
    for name, config in named:
        if not isinstance(config, AssetConfig):
            raise ConfigurationError(f"fleet: the configuration of {name} must be an AssetConfig")
    nx, nu, ny, np_ = first.observer.sizes
    regressor_columns = first.takes_regressor and first.regressor is None
    for name, config in named[1:]:
        sizes = config.observer.sizes
        for what, prefix, mine, theirs in (("nu", "u", nu, sizes[1]), ("ny", "y", ny, sizes[2])):
            if mine != theirs:
                column = f"{prefix}_{min(mine, theirs)}"
                raise ConfigurationError(
                    f"fleet: the observers' shapes differ: {first_name} has {what} = {mine}, {name} {what} = "
                    f"{theirs}, so column '{column}' is read by some assets and not by others")
        theirs_regressor = config.takes_regressor and config.regressor is None
        if theirs_regressor != regressor_columns or (regressor_columns and sizes[0::3] != (nx, np_)):
            raise ConfigurationError(
                f"fleet: the observers' shapes differ: {first_name} reads the regressor columns psi_i_j of a "
                f"{nx}x{np_ if regressor_columns else 0} regressor, {name} of a "
                f"{sizes[0]}x{sizes[3] if theirs_regressor else 0} one, so column 'psi_0_0' is read by some "
                "assets and not by others")
    inputs = tuple(f"u_{i}" for i in range(nu))
    outputs = tuple(f"y_{i}" for i in range(ny))
    regressor = tuple(f"psi_{i}_{j}" for i in range(nx) for j in range(np_)) if regressor_columns else ()
    for name in (*inputs, *outputs, *regressor):
        if name not in present:
            kind = {"u": "inputs", "y": "outputs", "p": "regressor entries"}[name[0]]
            raise ConfigurationError(f"fleet: the telemetry has no column '{name}': the observers read "
                                     f"{len(inputs) if name[0] == 'u' else len(outputs) if name[0] == 'y' else len(regressor)} "
                                     f"{kind} ({first_name}: nx, nu, ny, np = {nx}, {nu}, {ny}, {np_})")
    pattern = re.compile(r"^(u_\d+|y_\d+|psi_\d+_\d+)$")
    for name in columns:
        if pattern.match(name) and name not in (*inputs, *outputs, *regressor):
            raise ConfigurationError(f"fleet: column '{name}' is read by no observer ({first_name}: nx, nu, ny, "
                                     f"np = {nx}, {nu}, {ny}, {np_}{', regressor given' if not regressor else ''})")
    return TelemetryLayout(asset_column, time_column, inputs, outputs, regressor, (nx, nu, ny, np_))


# ---- checkpoints ------------------------------------------------------------------------------------


def _flatten(prefix: str, snapshot: dict, arrays: dict) -> list:
    """A snapshot's arrays into `arrays` under `prefix`; returns its (type, version)."""
    for name, value in snapshot["matrices"].items():
        arrays[f"{prefix}m/{name}"] = np.asarray(value, dtype=np.float64)
    for name, value in snapshot["integers"].items():
        arrays[f"{prefix}i/{name}"] = np.array(value, dtype=np.int64)
    return [snapshot["type"], snapshot["version"]]


def _unflatten(prefix: str, kind: list, arrays: Mapping) -> dict:
    snapshot = {"type": kind[0], "version": kind[1], "matrices": {}, "integers": {}}
    for key, value in arrays.items():
        if key.startswith(prefix + "m/"):
            snapshot["matrices"][key[len(prefix) + 2:]] = value
        elif key.startswith(prefix + "i/"):
            snapshot["integers"][key[len(prefix) + 2:]] = int(value)
    return snapshot


def _file_name(asset) -> str:
    text = str(asset)
    if re.fullmatch(r"[A-Za-z0-9_.-]{1,100}", text) and not text.startswith("."):
        return f"asset-{text}.ckpt"
    return f"asset-x{text.encode().hex()[:200]}.ckpt"


def _filesystem(directory: str):
    import fsspec

    fs, root = fsspec.core.url_to_fs(directory)
    fs.makedirs(root, exist_ok=True)
    return fs, root


def _digest(header: dict, payload: bytes) -> str:
    """SHA-256 of the header (all of it but the digest, canonical JSON) and the payload."""
    fields = {key: value for key, value in header.items() if key != "sha256"}
    return hashlib.sha256(json.dumps(fields, sort_keys=True).encode() + b"\n" + payload).hexdigest()


def write_checkpoint(fs, path: str, asset, position: int, observer, monitor, alarms: dict) -> None:
    """One asset's state after `position` samples: the observer's and monitor's snapshots and the
    alarms raised so far. The file is a line of magic, a line of JSON (format, asset, position, the
    snapshots' types and versions, the name, dtype, shape and offset of each array, the payload's
    length and the SHA-256 of all of it) and the arrays' bytes. It is written to a temporary name and
    moved into place, so that a reader sees the previous checkpoint or this one, never part of one."""
    arrays: dict = {}
    observer_kind = _flatten("observer/", observer.snapshot(), arrays)
    monitor_kind = _flatten("monitor/", monitor.snapshot(), arrays)
    for name, value in alarms.items():
        arrays[f"alarms/{name}"] = np.ascontiguousarray(value)
    index, chunks, offset = [], [], 0
    for name, value in arrays.items():
        index.append([name, value.dtype.str, list(value.shape), offset])
        chunks.append(value.tobytes())
        offset += value.nbytes
    payload = b"".join(chunks)
    header = {"format": CHECKPOINT_FORMAT, "asset": str(asset), "position": int(position),
              "observer": observer_kind, "monitor": monitor_kind, "arrays": index, "length": len(payload)}
    header["sha256"] = _digest(header, payload)
    temporary = f"{path}.partial-{os.getpid()}"
    with fs.open(temporary, "wb") as f:
        f.write(CHECKPOINT_MAGIC + json.dumps(header, sort_keys=True).encode() + b"\n" + payload)
    fs.mv(temporary, path)


def read_checkpoint(fs, path: str, asset, observer, monitor) -> Optional[tuple]:
    """The position and alarms of the asset's checkpoint at `path`, its snapshots restored into
    `observer` and `monitor`; None when there is none. Anything that does not check out (magic,
    header, length, SHA-256, format, the asset, the snapshots' types and versions) raises
    CheckpointError naming the asset and the file, and loads nothing."""
    if not fs.exists(path):
        return None
    with fs.open(path, "rb") as f:
        data = f.read()

    def refuse(why):
        raise CheckpointError(f"checkpoint of asset {asset!r} in file '{path}' refused: {why}")

    if not data.startswith(CHECKPOINT_MAGIC):
        refuse("it does not begin as an adaptobs fleet checkpoint")
    end = data.find(b"\n", len(CHECKPOINT_MAGIC))
    if end < 0:
        refuse("its header is truncated")
    try:
        header = json.loads(data[len(CHECKPOINT_MAGIC):end])
    except ValueError:
        header = None
    if not isinstance(header, dict):
        refuse("its header is corrupted")
    payload = data[end + 1:]
    if len(payload) != header.get("length"):
        refuse(f"truncated or extended: {len(payload)} bytes of payload, the header says {header.get('length')}")
    if _digest(header, payload) != header.get("sha256"):
        refuse("its SHA-256 checksum does not match: the file is corrupted")
    if header.get("format") != CHECKPOINT_FORMAT:
        refuse(f"checkpoint format {header.get('format')}, this version reads {CHECKPOINT_FORMAT}")
    if header.get("asset") != str(asset):
        refuse(f"it is the checkpoint of asset {header.get('asset')!r}")
    for name, obj in (("observer", observer), ("monitor", monitor)):
        expected = obj.snapshot()
        if header.get(name) != [expected["type"], expected["version"]]:
            refuse(f"its {name} snapshot is {header.get(name)}, this configuration's is "
                   f"{[expected['type'], expected['version']]}")
    arrays = {}
    for name, dtype, shape, offset in header["arrays"]:
        dtype = np.dtype(dtype)
        count = int(np.prod(shape, dtype=np.int64))
        arrays[name] = np.frombuffer(payload, dtype, count, offset).reshape(shape).copy()
    try:
        # A refused restore changes nothing; the caller discards both objects on any refusal.
        observer.restore(_unflatten("observer/", header["observer"], arrays))
        monitor.restore(_unflatten("monitor/", header["monitor"], arrays))
    except (ConfigurationError, TypeError, KeyError) as error:
        refuse(f"its snapshots do not fit this asset's configuration ({error})")
    alarms = {key[len("alarms/"):]: value for key, value in arrays.items() if key.startswith("alarms/")}
    return int(header["position"]), alarms


# ---- one partition ------------------------------------------------------------------------------------

ALARM_COLUMNS = ("sample", "t", "detector", "isolated", "direction", "statistic")


def _empty_alarms() -> dict:
    return {"sample": np.zeros(0, np.int64), "t": np.zeros(0), "detector": np.zeros(0, np.int8),
            "isolated": np.zeros(0, np.int64), "direction": np.zeros(0, np.int8), "statistic": np.zeros(0)}


def _chunk_alarms(out: dict, first: int, t: np.ndarray) -> dict:
    """The alarms FaultMonitor.run reported over a chunk whose first sample is `first`."""
    parts = []
    for code, name in enumerate(DETECTORS):
        raised = np.flatnonzero(out[f"{name}_alarm"])
        isolated = {"cusum": out["cusum_isolated"], "glr": out["glr_isolated"]}.get(name)
        parts.append({
            "sample": raised.astype(np.int64) + first,
            "t": t[raised],
            "detector": np.full(raised.size, code, np.int8),
            "isolated": (isolated[raised] if isolated is not None else np.full(raised.size, -1.0)).astype(np.int64),
            "direction": (out["cusum_direction"][raised] if name == "cusum" else np.zeros(raised.size)).astype(np.int8),
            "statistic": out[ALARM_STATISTIC[name]][raised],
        })
    return {key: np.concatenate([p[key] for p in parts]) for key in ALARM_COLUMNS}


def _concatenate(a: dict, b: dict) -> dict:
    return {key: np.concatenate([a[key], b[key]]) for key in ALARM_COLUMNS}


def _arrays(frame, layout: TelemetryLayout) -> tuple:
    """The partition's columns as float64 arrays, its rows ordered by asset (stable: each asset's rows
    keep their order), and where each asset's rows begin: one conversion for all assets, which are
    then slices."""
    ids = frame[layout.asset].to_numpy()
    order = None
    if ids.size > 1 and not np.all(ids[1:] >= ids[:-1]):
        order = np.argsort(ids, kind="stable")
        ids = ids[order]

    def columns(names):
        values = frame[list(names)].to_numpy(dtype=np.float64)
        return values if order is None else values[order]

    t = columns([layout.time])[:, 0]
    U = columns(layout.inputs) if layout.inputs else None
    Y = columns(layout.outputs)
    Psi = None
    if layout.regressor:
        nx, _, _, np_ = layout.sizes
        Psi = columns(layout.regressor).reshape(-1, nx, np_)
    starts = np.concatenate([[0], np.flatnonzero(ids[1:] != ids[:-1]) + 1, [ids.size]]) if ids.size else np.zeros(1, int)
    return ids, starts, t, U, Y, Psi


def _asset_arrays(frame, layout: TelemetryLayout, asset) -> tuple:
    """The time, inputs, outputs and regressors of the one asset of `frame`."""
    _, _, t, U, Y, Psi = _arrays(frame, layout)
    _require_increasing(t, layout, asset)
    return t, U, Y, Psi


def _require_increasing(t, layout, asset) -> None:
    if t.size > 1 and not np.all(t[1:] > t[:-1]):
        raise ConfigurationError(f"fleet: column '{layout.time}' of asset {asset!r} is not strictly increasing: "
                                 "sort each asset's samples by time, without repeats")


def process_partition(frame, layout: TelemetryLayout, configs: Mapping, default: Optional[AssetConfig],
                      checkpoint_dir: Optional[str] = None, every: int = 10_000) -> tuple:
    """Every asset of `frame` (a pandas DataFrame holding whole assets), each in chunks of `every`
    samples with a checkpoint after each when `checkpoint_dir` is given; an asset with a checkpoint
    resumes from it. Returns (alarms, finals): dicts of columns."""
    import pandas as pd

    if isinstance(frame, str):
        frame = pd.read_parquet(frame, columns=layout.columns)
    if layout.asset not in frame.columns and frame.index.name == layout.asset:
        frame = frame.reset_index()  # a Dask DataFrame indexed, and so partitioned, by asset
    fs = root = None
    if checkpoint_dir is not None:
        fs, root = _filesystem(checkpoint_dir)
    alarm_parts, finals = [], []
    ids, starts, t_all, U_all, Y_all, Psi_all = _arrays(frame, layout)
    for first, last in zip(starts[:-1], starts[1:]):
        asset = ids[first]
        asset = asset.item() if isinstance(asset, np.generic) else asset
        config = configs.get(asset, default)
        if config is None:
            raise ConfigurationError(f"fleet: asset {asset!r} has no configuration and there is no fleet-wide one")
        rows = slice(first, last)
        t, Y = t_all[rows], Y_all[rows]
        U = None if U_all is None else U_all[rows]
        Psi = config.regressor if Psi_all is None else Psi_all[rows]
        _require_increasing(t, layout, asset)
        observer = copy.deepcopy(config.observer)
        monitor = _core.FaultMonitor(config.design)
        position, alarms = 0, _empty_alarms()
        path = None
        if fs is not None:
            path = f"{root}/{_file_name(asset)}"
            restored = read_checkpoint(fs, path, asset, observer, monitor)
            if restored is not None:
                position, alarms = restored
                if position > t.size:
                    raise CheckpointError(f"checkpoint of asset {asset!r} in file '{path}' refused: it is at sample "
                                          f"{position}, the telemetry has {t.size}")
        samples = t.size
        # Chunks of `every` samples with or without checkpoints: they bound the memory of run()'s
        # per-sample results, and a run in chunks equals one run.
        while position < samples:
            end = min(position + every, samples)
            piece = slice(position, end)
            psi = Psi[piece] if Psi is not None and Psi.ndim == 3 else Psi
            y, absent = Y[piece], np.isnan(Y[piece])
            if absent.any():
                # A NaN output is a channel not measured: a masked update (an empty row is the time
                # update), and a sample the monitor passes over, its output error being incomplete.
                result = observer.run(None if U is None else U[piece], np.where(absent, 0.0, y), psi,
                                      present=~absent)
            else:
                result = observer.run(None if U is None else U[piece], y, psi)
            status = result.status.astype(np.int64)
            watched = max(0, min(config.monitor_from, end) - position)
            status[:watched] = int(_core.UpdateStatus.nonfinite_input)  # not monitored before convergence
            status[absent.any(axis=1)] = int(_core.UpdateStatus.nonfinite_input)
            out = monitor.run(result.parameters, result.output_error, status=status)
            alarms = _concatenate(alarms, _chunk_alarms(out, position, t[piece]))
            position = end
            if fs is not None:
                write_checkpoint(fs, path, asset, position, observer, monitor, alarms)
        alarm_parts.append((asset, alarms))
        health = observer.health
        finals.append({"asset": asset, "samples": samples, "steps": observer.step,
                       "state": observer.state, "parameters": observer.parameters,
                       "health": health.state.name, "health_step": health.step,
                       "alarms": int(alarms["sample"].size)})
    return alarm_parts, finals


# ---- the fleet ----------------------------------------------------------------------------------------


@dataclasses.dataclass
class FleetResult:
    """alarms: one row per alarm (asset, sample, t, detector, isolated, direction, statistic), by asset
    and sample; assets: one row per asset, its final estimates (x_i, theta_j) and health."""

    alarms: Any
    assets: Any


def _result(parts: list, layout: TelemetryLayout) -> FleetResult:
    import pandas as pd

    alarm_parts = [p for alarms, _ in parts for p in alarms]
    finals = [f for _, fs in parts for f in fs]
    seen = {}
    for index, final in enumerate(finals):
        if final["asset"] in seen:
            raise ConfigurationError(f"fleet: asset {final['asset']!r} appears in two partitions: partition the "
                                     f"telemetry by column '{layout.asset}'")
        seen[final["asset"]] = index
    order = sorted(range(len(finals)), key=lambda i: finals[i]["asset"])
    # One table of all alarms, by asset, then sample, then detector: the order of the partitions and of
    # the chunks does not show.
    parts = sorted(alarm_parts, key=lambda p: p[0])
    ranks = [np.lexsort((alarms["detector"], alarms["sample"])) for _, alarms in parts]
    columns = {layout.asset: np.concatenate([np.array([asset] * a["sample"].size, dtype=object)
                                             for asset, a in parts]) if parts else np.zeros(0, object)}
    for key in ALARM_COLUMNS:
        columns[key] = (np.concatenate([a[key][rank] for (_, a), rank in zip(parts, ranks)]) if parts
                        else _empty_alarms()[key])
    if all(isinstance(f["asset"], (int, np.integer)) and not isinstance(f["asset"], bool) for f in finals):
        columns[layout.asset] = columns[layout.asset].astype(np.int64)
    columns["detector"] = pd.Categorical.from_codes(columns["detector"].astype(np.int8), DETECTORS)
    alarms = pd.DataFrame(columns)
    nx, _, _, np_ = layout.sizes
    table = {layout.asset: [finals[i]["asset"] for i in order]}
    for key in ("samples", "steps", "alarms", "health", "health_step"):
        table[key] = [finals[i][key] for i in order]
    for j in range(nx):
        table[f"x_{j}"] = np.array([finals[i]["state"][j] for i in order], dtype=np.float64)
    for j in range(np_):
        table[f"theta_{j}"] = np.array([finals[i]["parameters"][j] for i in order], dtype=np.float64)
    return FleetResult(alarms=alarms, assets=pd.DataFrame(table))


def _split(config) -> tuple:
    if isinstance(config, AssetConfig):
        return {}, config
    if isinstance(config, Mapping):
        configs = dict(config)
        default = configs.pop(None, None)
        return configs, default
    raise ConfigurationError("fleet: argument 'config' must be an AssetConfig (fleet-wide) or a dict "
                             "{asset_id: AssetConfig} (key None: the fleet-wide default)")


def process(telemetry, config, *, client=None, checkpoint_dir: Optional[str] = None, every: int = 10_000,
            asset_column: str = "asset_id", time_column: str = "t", partitions: Optional[int] = None,
            timeout: Optional[float] = None) -> FleetResult:
    """Runs every asset's observer and FaultMonitor over its telemetry.

    telemetry: a pandas DataFrame, a Dask DataFrame (each partition holding whole assets), or a list of
      Parquet files (each holding whole assets); columns as the module's documentation says.
    config: an AssetConfig for every asset, or a dict {asset_id: AssetConfig} with key None for the rest.
    client: a dask.distributed Client; one task per partition (a pandas DataFrame is cut into
      `partitions` groups of whole assets, default two per worker). Without one, a loop in this process.
    checkpoint_dir: a directory or fsspec URL all workers reach; every `every` samples of an asset its
      observer's and monitor's snapshots and its alarms so far are written there, and a run finds them and
      resumes: the assets of a lost worker, rerun by the cluster, continue from their last checkpoint.
    The configuration and the columns are checked before any work: an unknown asset or time column, a
      missing input, output or regressor column, or observers of different shapes raise
      ConfigurationError naming the column.
    """
    configs, default = _split(config)
    if int(every) != every or every < 1:
        raise ConfigurationError("fleet: argument 'every' must be a positive integer (samples between checkpoints)")
    every = int(every)
    kind, columns = _telemetry_kind(telemetry)
    layout = _layout(columns, configs, default, asset_column, time_column)
    if kind == "pandas" and default is None:
        missing = sorted(set(telemetry[asset_column].unique().tolist()) - set(configs))
        if missing:
            raise ConfigurationError(f"fleet: column '{asset_column}' holds assets without a configuration and "
                                     f"there is no fleet-wide one: {missing[:5]}")
    if checkpoint_dir is not None:
        _filesystem(checkpoint_dir)
    arguments = (layout, configs, default, checkpoint_dir, every)
    if client is None:
        if kind == "pandas":
            pieces = [telemetry]
        elif kind == "parquet":
            pieces = list(telemetry)
        else:
            pieces = [p.compute() for p in telemetry.to_delayed()]
        return _result([process_partition(p, *arguments) for p in pieces], layout)
    if kind == "pandas":
        assets = np.sort(telemetry[asset_column].unique())
        count = partitions or 2 * max(1, len(client.scheduler_info().get("workers", {})))
        groups = [g for g in np.array_split(assets, min(count, max(len(assets), 1))) if g.size]
        pieces = [telemetry[telemetry[asset_column].isin(g)] for g in groups]
        # Each piece travels in its task, not scattered: the scheduler holds it and can rerun the task on
        # another worker when the one that had it dies (scattered data dies with its worker).
        futures = [client.submit(process_partition, p, *arguments, pure=False) for p in pieces]
    elif kind == "parquet":
        futures = [client.submit(process_partition, str(p), *arguments, pure=False) for p in telemetry]
    else:
        import dask

        futures = client.compute([dask.delayed(process_partition)(p, *arguments) for p in telemetry.to_delayed()])
    return _result(client.gather(futures) if timeout is None else _gather(client, futures, timeout), layout)


def _gather(client, futures, timeout):
    from distributed import wait

    wait(futures, timeout=timeout)
    return client.gather(futures)


def _telemetry_kind(telemetry) -> tuple:
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover
        pd = None
    if pd is not None and isinstance(telemetry, pd.DataFrame):
        return "pandas", list(telemetry.columns)
    if hasattr(telemetry, "to_delayed") and hasattr(telemetry, "columns"):
        index = [telemetry.index.name] if getattr(telemetry.index, "name", None) else []
        return "dask", index + list(telemetry.columns)
    if isinstance(telemetry, (str, os.PathLike)):
        raise ConfigurationError("fleet: argument 'telemetry' must be a list of Parquet files, not one path")
    if isinstance(telemetry, Sequence) and telemetry and all(isinstance(p, (str, os.PathLike)) for p in telemetry):
        import pyarrow.parquet as pq

        names = None
        for path in telemetry:
            these = list(pq.read_schema(str(path)).names)
            these = [n for n in these if not n.startswith("__index_level")]
            if names is not None and these != names:
                raise ConfigurationError(f"fleet: Parquet file '{path}' has columns {these}, the first one {names}")
            names = these
        return "parquet", names
    raise ConfigurationError("fleet: argument 'telemetry' must be a pandas DataFrame, a Dask DataFrame or a list "
                             "of Parquet files")


# ---- Monte Carlo --------------------------------------------------------------------------------------


def _block(function, seeds) -> list:
    return [function(int(seed)) for seed in seeds]


def map_seeds(client, function: Callable, seeds: int, *, first_seed: int = 0, block: int = 64) -> list:
    """[function(seed) for seed in first_seed .. first_seed + seeds - 1], one task per block of `block`
    seeds on the cluster of `client` (or in this process when client is None), in seed order."""
    if int(seeds) != seeds or seeds < 0:
        raise ConfigurationError("map_seeds: argument 'seeds' must be a non-negative integer")
    if int(block) != block or block < 1:
        raise ConfigurationError("map_seeds: argument 'block' must be a positive integer")
    all_seeds = np.arange(first_seed, first_seed + seeds, dtype=np.int64)
    blocks = [all_seeds[i:i + block] for i in range(0, int(seeds), int(block))]
    if client is None:
        return [r for b in blocks for r in _block(function, b)]
    futures = [client.submit(_block, function, b, pure=False) for b in blocks]
    return [r for part in client.gather(futures) for r in part]


def _recorded(run) -> tuple:
    if isinstance(run, _core.MonitoredRun):
        return (run.start, run.end, np.asarray(run.times), np.asarray(run.isolated))
    return tuple(run)


def _both_runs(scenario, seed):
    return _recorded(scenario(seed, True)), _recorded(scenario(seed, False))


class _Twins:
    """scenario(seed, True) and scenario(seed, False) of one seed, as recorded runs."""

    def __init__(self, scenario):
        self.scenario = scenario

    def __call__(self, seed):
        return _both_runs(self.scenario, seed)


def evaluate_detection(client, scenario: Callable, fault, seeds: int, *, first_seed: int = 0,
                       block: int = 64):
    """adaptobs.evaluate_detection(scenario, fault, seeds, first_seed=first_seed) with the simulations
    spread over a cluster, one task per block of seeds: each task runs scenario(seed, True) and
    scenario(seed, False) of its seeds and returns their alarms; the runs are then scored here, in seed
    order, by the evaluator itself. Each scenario is deterministic per seed, so the summary equals the
    single-process evaluator's exactly, on any number of workers and any block size."""
    runs = map_seeds(client, _Twins(scenario), seeds, first_seed=first_seed, block=block)
    faulty = [f for f, _ in runs]
    fault_free = [g for _, g in runs]
    return _core.evaluate_detection((faulty, fault_free), fault, seeds, first_seed=first_seed)
