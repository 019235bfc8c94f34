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


def test_painters_forked_before_the_solve_write_the_same_outputs(tmp_path):
    """What `drivedyn run` does: painters forked before the solve write results.nc and the figures
    after it; the same figures as drawn one by one, results.nc readable, the temporary pickle gone."""
    from drivedyn.core.plotting import Painters, save_result
    from drivedyn.core.results import open_result

    if threading.active_count() > 1:
        pytest.skip("threads running in this process: no painters are forked here")
    painters = Painters.start("drivedyn.belt.plots")
    assert painters is not None
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                         {"simulation.duration": 0.05, "output.frames": 2, "output.interval": "0.5 ms"})
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    with painters:
        r = drivedyn.run(m)
        saved = painters.submit(r, save_result, tmp_path / "b")
        painted = plot_all(r, tmp_path / "b", painters=painters)
        saved.result()
        pickled = painters._pickled[1]
    assert not __import__("os").path.exists(pickled)
    back = open_result(tmp_path / "b")
    assert np.array_equal(back.ds["span_tension"].values, r.ds["span_tension"].values)
    serial = plot_all(r, tmp_path / "a", workers=1)
    assert [p.name for p in serial] == [p.name for p in painted] and len(serial) >= 6
    for a, b in zip(serial, painted):
        ia, ib = np.asarray(Image.open(a)), np.asarray(Image.open(b))
        assert ia.shape == ib.shape and np.mean(ia != ib) < 0.01, a.name
