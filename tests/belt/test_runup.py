"""Run-up results: order tracking by crank angle against a synthetic signal of known orders, and
the FEAD run-up example end to end from the CLI (shortened)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
import xarray as xr

import drivedyn
from drivedyn.belt.dynamics.runup import add_runup, mean_angle
from drivedyn.core.model import from_dict, to_dict


def test_order_tracking_recovers_known_orders():
    # crank 1000 -> 4000 rpm in 3 s; a "span tension" of 300 N + 40 N at order 2 + 10 N at order 3
    # (phases on the crank angle) must come back per bin as 40 and 10, the other orders near 0
    d = to_dict(drivedyn.load(drivedyn.example_path("belt-5pk")))
    p0 = d["pulleys"][0]
    for k in ("torque_time",):
        p0.pop(k, None)
    p0["speed_time"] = [[0.0, 1000 / 60 * 2 * math.pi], [3.0, 4000 / 60 * 2 * math.pi]]
    m = from_dict(d)
    t = np.arange(1, 6001) * 5e-4
    phi = mean_angle(m.pulleys[0], t)
    assert phi[-1] == pytest.approx(2 * math.pi * (1000 + 4000) / 2 / 60 * 3.0, rel=1e-6)   # exact integral
    x = 300 + 40 * np.cos(2 * phi + 0.3) + 10 * np.cos(3 * phi - 1.0)
    ds = xr.Dataset({"span_tension": (("time", "span"), x[:, None]), "hub_load": (("time", "pulley"), np.tile(x[:, None], 2)),
                     "speed": (("time", "pulley"), np.ones((len(t), 2))), "pulley_radius": (("pulley",), np.ones(2))},
                    coords={"time": t, "span": ["a-b"], "pulley": ["driver", "driven"]})
    out = add_runup(ds, m, bin_width=250 / 60 * 2 * math.pi)["runup"]
    amp = ds["runup_tension_order"]
    assert len(out["speed_rpm"]) == 12
    assert np.allclose(amp.sel(order=2.0).values, 40, rtol=0.02)
    assert np.allclose(amp.sel(order=3.0).values, 10, rtol=0.05)
    assert np.all(amp.sel(order=1.0).values < 1.0) and np.all(amp.sel(order=4.0).values < 1.0)
    assert np.allclose(ds["runup_tension_mean"].values, 300, rtol=2e-3)


def test_fead_runup_from_the_cli(tmp_path):
    from typer.testing import CliRunner

    from drivedyn.front.cli import app

    m = drivedyn.replace(drivedyn.load(drivedyn.example_path("fead-runup")), {"simulation.duration": 1.2})
    path = tmp_path / "fead.toml"
    path.write_text(drivedyn.dumps(m))
    res = CliRunner().invoke(app, ["run", str(path), "--out", str(tmp_path / "out"), "--no-plots", "--quiet"])
    assert res.exit_code == 0, res.output
    assert "run-up of crankshaft" in res.output
    s = json.loads((tmp_path / "out" / "summary.json").read_text())
    ru = s["runup"]
    rpm = np.array(ru["speed_rpm"])
    assert rpm.min() < 900 and rpm.max() > 1100                  # idle 800 rpm, then up to 1220 rpm
    for sp in ru["span_tension_max"]:
        assert np.all(np.array(ru["span_tension_min"][sp]) <= np.array(ru["span_tension_max"][sp]))
    # the tensioner works: its arm moves and the slack span it sits on keeps its tension
    assert max(ru["arm_travel_range"]["tensioner"]) > 1e-3
    assert min(ru["span_tension_min"]["tensioner-crankshaft"]) > 50
    # creep stays creep at idle and above (no gross slip in the run-up)
    assert all(abs(v) < 0.03 for vals in ru["slip"].values() for v in vals), ru["slip"]
    assert s["tensioners"]["tensioner"]["rest_tension"] == pytest.approx(350, rel=0.05)


def test_a_run_down_is_read_apart_from_the_run_up():
    """Up to 1500 rpm and back to 800: the bins of the run-down follow the run-up's, in falling
    speed, each bin's tension extremes those of its own samples (recomputed here from the time
    series and the crank's prescribed mean speed); the run-down's window stores negative power
    (the drive gives back kinetic energy) and the efficiency leaves it out (output over output
    plus losses, below 1); the crank, held at its prescribed speed, reports the torque that holds
    it (torque x speed = its power within 3 %, the window means of a product and of its factors)."""
    d = to_dict(drivedyn.load(drivedyn.example_path("fead-runup")))
    w = lambda rpm: -rpm * math.pi / 30
    d["pulleys"][0]["speed_time"] = [[0, 0], [0.3, w(800)], [0.4, w(800)], [0.8, w(1500)], [1.2, w(800)]]
    d["simulation"]["duration"] = 1.2
    d["belt"]["segments"] = 150
    d["output"].update(runup_bin="250 rpm", steady_window=[0.9, 1.2])
    r = drivedyn.run(from_dict(d))
    ru, ds = r.summary["runup"], r.ds
    sweep, rpm = ru["sweep"], ru["speed_rpm"]
    k = sweep.index("down")
    assert set(sweep[:k]) == {"up"} and set(sweep[k:]) == {"down"}
    assert rpm[:k] == sorted(rpm[:k]) and rpm[k:] == sorted(rpm[k:], reverse=True)
    t = ds["time"].values
    crank = np.abs(np.interp(t, [0, 0.3, 0.4, 0.8, 1.2], [0, 800, 800, 1500, 800]))
    falling = t > 0.8
    span = ds["span"].values[0]
    ten = ds["span_tension"].sel(span=span).values
    for b in (k - 1, k):                      # the top bin of each sweep
        sel = (np.abs(crank - rpm[b]) <= 125) & (t >= 0.3) & (falling if sweep[b] == "down" else ~falling)
        assert ru["span_tension_min"][span][b] == pytest.approx(ten[sel].min(), rel=1e-9)
        assert ru["span_tension_max"][span][b] == pytest.approx(ten[sel].max(), rel=1e-9)
    p = r.summary["power"]
    assert p["stored"] < 0 and 0 < p["efficiency"] < 1
    c = r.summary["pulleys"]["crankshaft"]
    assert c["torque_mean"] * c["speed_mean"] == pytest.approx(c["power_mean"], rel=0.03)
