"""Span stability from the run (belt/dynamics/span_stability.py): each span's tension fluctuation
on its own Mathieu tongues, in the summary and the verdict."""
from __future__ import annotations

import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.dynamics import span_stability as S
from drivedyn.mechanics.layout import compute_layout
from drivedyn.mechanics.span.frequencies import span_frequencies
from drivedyn.mechanics.span.quantities import SpanProperties, effective_tension

# the seed's T10 belt (seed 002: l = 0.3 m, rhoA = 0.084 kg/m with the density read as 3e3 kg/m^3, EI = 0.045 N m^2)
SPAN = SpanProperties(0.3, 0.084, 0.045, 0.02)
T0, V = 300.0, 10.0


def _f1():
    return float(span_frequencies(T0, SPAN.mass_per_length, SPAN.length, SPAN.bending_stiffness, V, 1)["moving_beam"][0])


@pytest.fixture(scope="module")
def run_5pk():
    """examples/belt-5pk.toml, rotational model, 0.6 s (the driver's ramp and the window after it)."""
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("belt-5pk")),
                         {"simulation.model": "rotational", "simulation.duration": 0.6})
    return m, drivedyn.run(m)


def _series(fe, dT, duration=0.5, rate=20e3):
    t = np.arange(int(duration * rate)) / rate
    return t, T0 + dT * np.cos(2 * math.pi * fe * t + 0.3) + 0.01 * dT * np.cos(2 * math.pi * 0.37 * fe * t)


@pytest.mark.parametrize("ratio,inside", [(2.0, True), (1.5, False)])
def test_synthetic_fluctuation_at_twice_f1_is_inside(ratio, inside):
    """A tension fluctuation at exactly 2 f1 with depth dT / N = 0.2 (above the principal tongue's
    threshold 4 zeta = 0.08, Nayfeh & Mook 1979, sec. 5.2.6) is inside; at 1.5 f1 it is not (tongue
    1's band at that depth spans about 2 f1 (1 -+ 0.05); tongue 2 is at f1)."""
    f1 = _f1()
    N = float(effective_tension(T0, V, SPAN))
    dT = 0.2 * N
    t, x = _series(ratio * f1, dT)
    mean, comps = S.largest_components(t, x)
    # the window's plain mean (as summary.spans), off by at most dT / (pi f_e duration) over a part period
    assert mean == pytest.approx(T0, abs=dT / (math.pi * ratio * f1 * 0.5))
    # the peak's frequency within 0.016 of a bin (1 / duration: Hann window, parabola on the log
    # magnitudes), its amplitude by least squares within 5e-4 (test_peak_refinement_over_a_bin)
    assert comps[0][0] == pytest.approx(ratio * f1, abs=0.016 / 0.5)
    assert comps[0][1] == pytest.approx(dT, rel=5e-4)
    e = S.span_entry(SPAN, mean, V, comps, SPAN.damping_ratio, f_driver=10.0)
    assert e["frequency_1"] == pytest.approx(f1, rel=1e-3)      # at the window's mean tension
    assert e["inside"] is inside
    c = e["components"][0]
    assert c["tongue"] == 1 and c["inside"] is inside
    if inside:
        assert e["tongue_distance"] == 0.0
    else:
        assert e["tongue_distance"] > 0.2          # 1.5 f1 lies 25 % below the principal tongue's centre


def test_peak_refinement_over_a_bin():
    """One sinusoid swept across a bin of the spectrum: frequency within 0.016 of a bin and amplitude
    within 5e-4 (the Hann window's parabolic peak on log magnitudes: Gade & Herlufsen 1987 give a
    bias below 0.02 bin)."""
    rate, n = 20e3, 10000
    t, df = np.arange(n) / rate, rate / n
    for off in np.linspace(0.0, 1.0, 21):
        f = (97 + off) * df
        _, c = S.largest_components(t, 5.0 * np.cos(2 * math.pi * f * t + 0.3))
        assert abs(c[0][0] - f) < 0.016 * df and abs(c[0][1] - 5.0) < 5e-4 * 5.0


def test_depth_below_threshold_is_not_inside():
    """The same at 2 f1 with depth 0.06 < 4 zeta: the damped tongue is closed."""
    f1 = _f1()
    t, x = _series(2 * f1, 0.06 * float(effective_tension(T0, V, SPAN)))
    mean, comps = S.largest_components(t, x)
    e = S.span_entry(SPAN, mean, V, comps, SPAN.damping_ratio, f_driver=10.0)
    assert e["inside"] is False and e["nearest"]["open"] is False


def test_run_span_frequency_is_the_span_analysis(run_5pk):
    """The f1 of each span in summary.span_stability is the span analysis's moving beam
    (mechanics.span.frequencies) for the same span (length from the layout, m, EI, the run's mean
    tension and belt speed), and Mote's moving string f1 = c (1 - V^2 / c^2) / (2 L), c = sqrt(T / m)
    (Wickert & Mote 1990), to 1e-4 (the 5PK belt's EI adds pi^2 EI / L^2 = 0.008 N to 280-830 N)."""
    m, r = run_5pk
    spans = {sp.name: sp for sp in compute_layout(m).spans}
    st = r.summary["span_stability"]["spans"]
    assert set(st) == set(spans)
    for name, e in st.items():
        L = spans[name].length
        f = span_frequencies(e["tension_mean"], m.belt.mass_per_length, L, m.belt.bending_stiffness, e["speed"], 1)
        assert e["frequency_1"] == pytest.approx(float(f["moving_beam"][0]), rel=1e-9)
        c = math.sqrt(e["tension_mean"] / m.belt.mass_per_length)
        assert e["frequency_1"] == pytest.approx(c * (1 - e["speed"] ** 2 / c ** 2) / (2 * L), rel=1e-4)


def test_run_numbers_present_and_consistent(run_5pk):
    """On a short run of examples/belt-5pk.toml: every span has its mean (within 1 % of
    summary.spans.*.tension_mean), components no larger than half the tension's band, a distance to
    its nearest tongue; the verdict judges span_stability and the printed tables show it."""
    from drivedyn.front.overview import tables

    _, r = run_5pk
    s = r.summary
    for name, e in s["span_stability"]["spans"].items():
        sp = s["spans"][name]
        assert e["tension_mean"] == pytest.approx(sp["tension_mean"], rel=0.01)
        assert e["components"], name
        half = 0.5 * (sp["tension_max"] - sp["tension_min"])
        for c in e["components"]:
            assert 0 < c["amplitude"] <= half * 1.001
            assert c["depth"] == pytest.approx(c["amplitude"] / e["effective_tension"])
        assert e["tongue_distance"] is not None and e["tongue_distance"] >= 0
        assert e["inside"] is False
    crit = s["criteria"]["span_stability"]
    assert crit["value"] == 0 and crit["pass"] and "nearest" in crit["where"]
    t = [t for t in tables(r) if t["title"].startswith("span stability")]
    assert t and len(t[0]["rows"]) == len(s["spans"])


def test_runup_flags_the_bins_inside():
    """A run-up (examples/fead-runup.toml, rotational) places each bin's tracked orders: the
    criterion counts the spans with a bin inside, and names them (the example's alternator-tensioner
    span is the one its header says the 2nd and 4th orders excite)."""
    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")), {"simulation.model": "rotational"})
    s = drivedyn.run(m).summary
    st = s["span_stability"]
    inside = [n for n, e in st["spans"].items() if e["inside"]]
    assert inside == st["inside"]
    for n in inside:
        e = st["spans"][n]
        assert e["rpm"] in e["inside_rpm"]
        assert e["components"][0]["order"] == pytest.approx(round(e["components"][0]["order"]))
    assert s["criteria"]["span_stability"]["value"] == len(inside)
    assert "alternator-tensioner" in inside


def test_segment_model_run_has_it(model_factory):
    """The segment model (the seed's 5PK drive at 100 segments, 0.2 s held at 20 rad/s) writes it too;
    a component at the segments' passing frequency (the chain's polygon effect) is listed, not placed."""
    m = model_factory(**{"simulation.duration": 0.2, "output.steady_window": [0.1, 0.2],
                         "pulleys": [dict(name="driver", center=[0.0, 0.0], radius=0.027, inertia=0.02,
                                          speed_time=[[0.0, -20.0], [1.0, -20.0]]),
                                     dict(name="driven", center=[0.515, 0.0], radius=0.027, inertia=0.02,
                                          torque_time=[[0.0, 2.0], [1.0, 2.0]])]})
    r = drivedyn.run(m)
    st = r.summary["span_stability"]["spans"]
    for name, e in st.items():
        assert e["tension_mean"] == pytest.approx(r.summary["spans"][name]["tension_mean"], rel=0.01)
        assert e["frequency_1"] > 0 and e["components"]
    passing = 20.0 * 0.027 * 100 / r.summary["belt"]["path_length"]
    for e in st.values():
        for c in e["components"]:
            k = round(c["frequency"] / passing)
            if k >= 1 and abs(c["frequency"] - k * passing) < 0.02 * k * passing:
                assert "segment passing" in c["note"] and "tongue" not in c
