"""The README's Python example runs as printed (matplotlib replaced by a stub
that records the plotted arrays), so that it cannot rot."""

import pathlib
import re
import sys
import types

import numpy as np

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def test_the_readme_example_runs_and_estimates_the_thrust_efficiencies(monkeypatch, capsys):
    text = README.read_text(encoding="utf-8")
    section = text[text.index("## Python"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    plotted = []
    pyplot = types.SimpleNamespace(plot=lambda *a, **k: plotted.append(a), xlabel=lambda *a: None,
                                   ylabel=lambda *a: None, show=lambda: None)
    matplotlib = types.ModuleType("matplotlib")
    matplotlib.pyplot = pyplot
    monkeypatch.setitem(sys.modules, "matplotlib", matplotlib)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", pyplot)
    namespace = {}
    exec(compile(code, str(README), "exec"), namespace)
    theta = namespace["result"].parameters
    assert theta.shape == (3000, 2)
    assert np.linalg.norm(theta[-1] - [1.0, 1.5]) < 0.02
    assert plotted and plotted[0][1] is theta
    assert "[1.00786" in capsys.readouterr().out
