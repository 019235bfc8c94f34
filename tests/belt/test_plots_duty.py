"""Plots that show what is there, on the shipped supplier-style drive (examples/fead-ag0868.toml, its
run cut short on the rotational model): the prescribed crank left out of the speed spectra (its
round-off stretched the log axis over 18 decades); the Campbell diagram over the duty cycle's
speeds (800-2000 rpm) with the one-speed run as a line, no band of no width, circles only for the
crossings the verdict lists (the crank declares no speed orders: none), legend entries only for
what is drawn; energy legends in words; hub-load directions with no "-0"."""
from __future__ import annotations

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.plots import _figures


@pytest.fixture(scope="module")
def figures():
    m = drivedyn.load(drivedyn.example_path("fead-ag0868"))
    m = drivedyn.replace(m, {"simulation.model": "rotational", "simulation.duration": 0.2,
                             "output.steady_window": [0.15, 0.2], "duty_cycle.dynamic": False,
                             "duty_cycle.tolerance": False, "duty_cycle.acceleration": None,
                             "pulleys.0.speed_time": [[0, 0], [0.1, -83.7758], [0.2, -83.7758]]})
    res = drivedyn.run(m)
    jobs = dict(_figures(res.ds, res.summary["driver"]))
    return res, {name: jobs[name]() for name in {"campbell.png", "spectrum.png", "tensions.png", "energy.png"} & set(jobs)}


def _labels(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else []


def test_campbell_over_the_duty_cycles_speeds(figures):
    res, figs = figures
    ax = figs["campbell.png"].axes[0]
    assert ax.get_xlim()[1] >= 2000                         # the duty cycle reaches 2000 rpm
    widths = [p.get_width() for p in ax.patches if hasattr(p, "get_width")]
    assert widths and min(widths) > 1.0, widths             # no band of no width ("run: 800-800 rpm")
    labels = _labels(ax)
    assert "duty cycle: 800-2000 rpm" in labels and "run: 800 rpm" in labels, labels
    red = [ln for ln in ax.get_lines() if ln.get_marker() in ("o", "s") and ln.get_xdata().size]
    counted = res.summary.get("criteria", {}).get("resonance_crossings", {}).get("value", 0)
    assert len(red) == counted == 0, (len(red), counted)   # the crank declares no speed orders: nothing counted
    assert "squares" not in ax.get_title() and not any("cross" in x for x in labels), (ax.get_title(), labels)


def test_the_prescribed_crank_left_out_of_the_speed_spectra(figures):
    _, figs = figures
    ax = figs["spectrum.png"].axes[1]
    names = [ln.get_label() for ln in ax.get_lines() if not ln.get_label().startswith("_")]
    assert "CRK" not in names and {"A_C", "TEN"} <= set(names), names
    lo, hi = ax.get_ylim()
    assert np.log10(hi / lo) < 8, (lo, hi)                  # was 18 decades of the crank's round-off
    assert "CRK: prescribed" in ax.get_title()


def test_legends_in_words_and_no_minus_zero(figures):
    _, figs = figures
    texts = [t for f in figs.values() for a in f.axes for t in _labels(a)]
    assert texts
    assert not [t for t in texts if "_damping" in t or "_force" in t], texts
    hub = _labels(figs["tensions.png"].axes[1])
    assert hub and not [t for t in hub if "-0 deg" in t or "towards -" in t], hub
