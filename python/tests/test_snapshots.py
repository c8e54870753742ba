"""State that survives a process: snapshot, pickle and deepcopy continue bit
for bit; a snapshot of another class or version is refused."""

import copy
import pickle
import subprocess
import sys

import numpy as np
import pytest

import adaptobs
from conftest import make_filter, make_observer


@pytest.mark.parametrize("make", [make_observer, make_filter])
@pytest.mark.parametrize("clone", [copy.deepcopy, copy.copy, lambda o: pickle.loads(pickle.dumps(o))])
def test_a_copy_continues_bit_for_bit(satellite, make, clone):
    system, data = satellite
    options = {"excitation_window": 40, "normalized_step": True} if make is make_observer else {}
    original = make(system, **options)
    original.run(data["U"][:500], data["Y"][:500], data["Psi"][:500])
    twin = clone(original)
    assert twin is not original
    a = original.run(data["U"][500:], data["Y"][500:], data["Psi"][500:])
    b = twin.run(data["U"][500:], data["Y"][500:], data["Psi"][500:])
    assert np.array_equal(a.state, b.state)
    assert np.array_equal(a.parameters, b.parameters)
    for name in a.diagnostics:
        assert np.array_equal(a.diagnostics[name], b.diagnostics[name], equal_nan=True)
    assert original.step == twin.step == 3000


def test_a_pickle_continues_bit_for_bit_in_another_process(satellite, tmp_path):
    system, data = satellite
    observer = make_observer(system, excitation_window=40)
    observer.run(data["U"][:1000], data["Y"][:1000], data["Psi"][:1000])
    (tmp_path / "observer.pickle").write_bytes(pickle.dumps(observer))
    script = f"""
import pickle, numpy as np, adaptobs
observer = pickle.loads(open({str(tmp_path / 'observer.pickle')!r}, 'rb').read())
data = adaptobs.examples.simulate_satellite(3000, noise=0.01, seed=2003)
result = observer.run(data['U'][1000:], data['Y'][1000:], data['Psi'][1000:])
np.save({str(tmp_path / 'theta.npy')!r}, result.parameters)
"""
    subprocess.run([sys.executable, "-c", script], check=True)
    expected = observer.run(data["U"][1000:], data["Y"][1000:], data["Psi"][1000:]).parameters
    assert np.array_equal(np.load(tmp_path / "theta.npy"), expected)


def test_a_snapshot_of_another_class_or_version_is_refused(satellite):
    system, data = satellite
    observer = make_observer(system)
    akf = make_filter(system)
    with pytest.raises(adaptobs.ConfigurationError,
                       match="restore: argument 'snapshot' is of a AugmentedKalmanFilter, not of a GuyaderZhangObserver"):
        observer.restore(akf.snapshot())
    state = observer.snapshot()
    state["version"] = 99
    with pytest.raises(adaptobs.ConfigurationError, match="is version 99 of GuyaderZhangObserver; this build reads version 1"):
        observer.restore(state)
    other = make_observer(system, excitation_window=10)
    with pytest.raises(adaptobs.ConfigurationError, match="holds 'excitation_window' = 10 where this GuyaderZhangObserver has 0"):
        observer.restore(other.snapshot())


def test_restore_moves_an_observer_to_the_saved_state(satellite):
    system, data = satellite
    observer = make_observer(system)
    observer.run(data["U"][:200], data["Y"][:200], data["Psi"][:200])
    saved = observer.snapshot()
    first = observer.run(data["U"][200:400], data["Y"][200:400], data["Psi"][200:400]).parameters
    observer.restore(saved)
    again = observer.run(data["U"][200:400], data["Y"][200:400], data["Psi"][200:400]).parameters
    assert np.array_equal(first, again)
    assert set(saved) == {"type", "version", "matrices", "integers"}
    assert saved["matrices"]["theta"].shape == (2, 1)
