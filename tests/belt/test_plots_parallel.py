"""The belt figures drawn in two forked processes are the same files as drawn one by one."""
import threading

import numpy as np
import pytest
from PIL import Image

import drivedyn
from drivedyn.belt.plots import plot_all


def test_parallel_figures_equal_serial(tmp_path):
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                         {"simulation.duration": 0.05, "output.frames": 2, "output.interval": "0.5 ms"})
    r = drivedyn.run(m)
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    serial = plot_all(r, tmp_path / "a", workers=1)
    if threading.active_count() > 1:
        pytest.skip("threads running in this process: the figures are drawn one by one here")
    saved = []
    parallel = plot_all(r, tmp_path / "b", workers=2, meanwhile=lambda: saved.append(r.save(tmp_path / "b")))
    assert saved and (tmp_path / "b" / "results.nc").exists()
    assert [p.name for p in serial] == [p.name for p in parallel] and len(serial) >= 6
    for a, b in zip(serial, parallel):
        ia, ib = np.asarray(Image.open(a)), np.asarray(Image.open(b))
        assert ia.shape == ib.shape and np.mean(ia != ib) < 0.01, a.name     # same figure (fonts may hint differently)
