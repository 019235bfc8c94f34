"""Span flap (belt/steady/flap.py) against closed forms: the axially moving string (Mote 1965; Wickert &
Mote 1990) f_1 = c (1 - V^2/c^2) / 2L, c = sqrt(T/m), and the pinned tensioned beam at rest
f_1 = sqrt((T + pi^2 EI / L^2) / m) / 2L; and a crossing placed on purpose (a span whose first flap
mode meets order 2 at 3000 rpm) is found and listed."""
from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

import drivedyn
from drivedyn.belt.steady import flap as flapmod
from drivedyn.mechanics.layout import compute_layout


def _model(EI=1e-12):
    m = drivedyn.load(drivedyn.example_path("belt-5pk"))
    return drivedyn.replace(m, {"belt.bending_stiffness": EI})


def _steady(model, rpm, tension):
    """A steady run's ds and summary as flap() reads them (driver speed, span mean tensions)."""
    names = [p.name for p in model.pulleys]
    ds = xr.Dataset(coords={"pulley": names})
    ds["pulley_radius"] = ("pulley", np.array([p.radius for p in model.pulleys]))
    lay = compute_layout(model)
    summary = {"driver": names[0], "pulleys": {names[0]: {"speed_mean": rpm * math.pi / 30}},
               "spans": {sp.name: {"tension_mean": tension} for sp in lay.spans}}
    return ds, summary


@pytest.mark.parametrize("rpm", [0.0, 3000.0, 9000.0])
def test_moving_string_closed_form(rpm):
    model = _model()
    T, m = 300.0, model.belt.mass_per_length
    ds, s = _steady(model, rpm, T)
    fl = flapmod.flap(model, ds, s)
    V = rpm * math.pi / 30 * model.pulleys[0].radius
    c = math.sqrt(T / m)
    for sp in compute_layout(model).spans:
        exact = c * (1 - V ** 2 / c ** 2) / (2 * sp.length)
        got = fl["spans"][sp.name]["f1"][0]
        assert got == pytest.approx(exact, rel=0.005), (sp.name, rpm, got, exact)
    assert fl["belt_speed"][0] == pytest.approx(V)


def test_bending_at_rest_is_the_pinned_beam():
    EI = 0.05
    model = _model(EI)
    T, m = 200.0, model.belt.mass_per_length
    ds, s = _steady(model, 0.0, T)
    fl = flapmod.flap(model, ds, s)
    for sp in compute_layout(model).spans:
        exact = math.sqrt((T + math.pi ** 2 * EI / sp.length ** 2) / m) / (2 * sp.length)
        assert fl["spans"][sp.name]["f1"][0] == pytest.approx(exact, rel=0.005)
        assert fl["spans"][sp.name]["f2"][0] == pytest.approx(
            math.sqrt((T + 4 * math.pi ** 2 * EI / sp.length ** 2) / m) / sp.length, rel=0.005)


def test_beyond_critical_speed_has_no_frequency():
    # T = 10 N < m V^2 = 40 N; below it the same span has its string frequency
    assert flapmod.span_frequencies([10.0, 10.0], 0.1, 0.3, 0.0, [20.0, 0.0]).tolist() == \
        [[0.0, 0.0], pytest.approx([math.sqrt(100.0) / 0.6, 2 * math.sqrt(100.0) / 0.6])]


def test_crossing_placed_at_3000_rpm_is_listed():
    """Order 2 at 3000 rpm is 100 Hz: the span tension is set so that the first flap mode of one
    span is 100 Hz at the belt speed of 3000 rpm; over a run-up with that tension in every bin,
    the crossing is found at 3000 rpm (to the interpolation between bins)."""
    model = _model()
    lay = compute_layout(model)
    m, r = model.belt.mass_per_length, model.pulleys[0].radius
    sp = lay.spans[0]
    V = 3000 * math.pi / 30 * r
    # c (1 - V^2/c^2) / 2L = 100  ->  c^2 - 200 L c - V^2 = 0
    c = 100 * sp.length + math.sqrt((100 * sp.length) ** 2 + V ** 2)
    T = m * c ** 2
    rpm = np.arange(1000.0, 5001.0, 250.0)
    names = [p.name for p in model.pulleys]
    ds = xr.Dataset(coords={"pulley": names, "speed_bin": rpm, "span": [s.name for s in lay.spans]})
    ds["pulley_radius"] = ("pulley", np.array([p.radius for p in model.pulleys]))
    ds["runup_tension_mean"] = (("speed_bin", "span"), np.full((len(rpm), len(lay.spans)), T))
    fl = flapmod.flap(model, ds, {"runup": {"crank": names[0]}})
    xs = flapmod.crossings(fl, [2.0], (1000, 5000))
    mine = [x for x in xs if x["span"] == sp.name]
    assert len(mine) == 1
    assert mine[0]["rpm"] == pytest.approx(3000, rel=0.005)
    assert mine[0]["frequency_hz"] == pytest.approx(100, rel=0.005)
    # outside the judged range: not listed
    assert not [x for x in flapmod.crossings(fl, [2.0], (3500, 5000)) if x["span"] == sp.name]


def test_a_negative_flap_order_is_refused():
    """criteria.flap_orders = [-2] was accepted and never judged: refused naming the field."""
    import pytest

    import drivedyn

    model = drivedyn.load(drivedyn.example_path("fead-runup"))
    with pytest.raises(drivedyn.ModelError, match=r"criteria.flap_orders.*\(0, 1000\]"):
        drivedyn.replace(model, {"criteria.flap_orders": [-2.0]})


def test_crossings_judged_by_what_excites_the_span():
    """fead-runup's rotational run-up: a crank order at f1 excites only a span whose end moves with
    the tensioner (direct); on spans between fixed pulleys it is listed, not counted (all nine
    crossings counted before); an order at 2 f1 counts where the tension modulation exceeds the
    damped Mathieu threshold 4 zeta, so raising zeta above a crossing's modulation / 4 drops it."""
    import drivedyn

    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")), {"simulation.model": "rotational"})
    r = drivedyn.run(m)
    c = r.summary["criteria"]["flap_crossings"]
    xs = c["details"]
    tensioner_spans = {"alternator-tensioner", "tensioner-crankshaft"}
    for x in xs:
        if x["kind"] == "direct":
            assert x["span"] in tensioner_spans and x["counted"] and x["amplitude"] > 0
        elif x["kind"] == "none":
            assert x["span"] not in tensioner_spans and not x["counted"]
        else:
            assert x["frequency_hz"] == pytest.approx(2 * np.interp(x["rpm"], r.summary["flap"]["speed_rpm"],
                                                                    r.summary["flap"]["spans"][x["span"]]["f1"]), rel=1e-6)
            assert x["counted"] == (x["modulation"] > 4 * 0.02)
    assert c["value"] == sum(x["counted"] for x in xs) < len(xs)
    assert any(x["kind"] == "none" for x in xs) and "flap_crossings_listed" in r.summary["criteria_skipped"]
    par = [x for x in xs if x["kind"] == "parametric" and x["counted"]]
    assert par
    zeta = 1.01 * max(x["modulation"] for x in par) / 4
    r2 = drivedyn.run(drivedyn.replace(m, {"criteria.flap_damping_ratio": zeta}))
    assert not [x for x in r2.summary["criteria"]["flap_crossings"]["details"] if x["kind"] == "parametric" and x["counted"]]


def test_orders_all_below_the_amplitude_limit_are_said_so():
    """criteria.flap_amplitude_min above every declared speed order left nothing judged, and the
    verdict said "the crank declares no speed orders" (it declares two)."""
    import drivedyn

    model = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")),
                             {"simulation.model": "rotational", "simulation.runup": "periodic",
                              "output.runup_bin": "1000 rpm", "criteria.flap_amplitude_min": "100 rad/s"})
    why = drivedyn.run(model).summary["criteria_skipped"]["flap_crossings"]
    assert "weaker than criteria.flap_amplitude_min (100 rad/s)" in why
