"""Friction laws, friction zones and excitation: equivalences and closed forms."""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.belt.dynamics import _bodies as BK
from drivedyn.belt.segments.system import build


def kinematic(model_factory, **kw):
    args = dict(pulleys__0__speed_time=[[0, 0], [0.05, -40.0]], pulleys__1__viscous_torque=5.0 / 40,
                pulleys__1__inertia=2e-3, simulation__duration=0.3, output__steady_window=[0.15, 0.3])
    args.update(kw)
    return model_factory(**args)


def test_threlfall_law_shape():
    dv = 1e-3
    assert BK.threlfall(0.0, dv) == 0.0
    assert BK.threlfall(dv, dv) == 1.0 and BK.threlfall(-2 * dv, dv) == -1.0
    assert BK.threlfall(0.5 * dv, dv) == pytest.approx(0.5 * 0.5 * (3 - 0.25))
    # the implicit update solves s + a mu(s) = w exactly, in and out of the band
    for w in (-1.0, -1.5e-3, -1e-4, 0.0, 3e-4, 2e-3, 0.7):
        sl = BK.solve_threlfall(w, 0.4, dv)
        assert sl + 0.4 * BK.threlfall(sl, dv) == pytest.approx(w, abs=1e-12)


def test_friction_zone_over_the_whole_belt_equals_the_global_coefficient(model_factory):
    a = drivedyn.run(kinematic(model_factory, friction__coefficient=0.4, simulation__duration=0.1, output__steady_window=None))
    b = drivedyn.run(kinematic(model_factory, friction__coefficient=1.0, simulation__duration=0.1, output__steady_window=None,
                               friction__zones=[{"start": 0.0, "end": 10.0, "coefficient": 0.4}]))
    np.testing.assert_allclose(a.ds["speed"].values, b.ds["speed"].values, rtol=0, atol=1e-12)


def test_friction_zone_marks_the_right_segments(model_factory):
    m = model_factory(friction__zones=[{"start": 0.1, "end": 0.3, "coefficient": 0.05}])
    sysm = build(m)
    pitch = 1.1956 / 100   # unstretched length / n, stretched by 0.36 %
    s_mid = (np.arange(100) + 0.5) * pitch * (1 + 550 / 1.52e5)
    inside = (s_mid >= 0.1) & (s_mid < 0.3)
    assert np.all(sysm.contact.mu[inside] == 0.05) and np.all(sysm.contact.mu[~inside] == 1.0)


def test_oily_stretch_slips_when_it_crosses_the_driven_pulley(model_factory):
    # a 0.2 m stretch with mu = 0.05 cannot carry 5 N m: the driven pulley slips while it passes
    m = kinematic(model_factory, simulation__duration=0.6,
                  friction__zones=[{"start": 0.6, "end": 0.8, "coefficient": 0.05}])
    r = drivedyn.run(m)
    w = r.ds["speed"].values
    ratio = w[:, 1] / np.where(np.abs(w[:, 0]) > 1, w[:, 0], np.nan)
    assert np.nanmin(ratio[100:]) < 0.9          # a slip event
    assert np.nanmax(ratio[100:]) > 0.99         # and normal creep outside it


def test_elastic_plastic_law_transmits_the_same_torque(model_factory):
    a = drivedyn.run(kinematic(model_factory)).summary
    b = drivedyn.run(kinematic(model_factory, friction__law="elastic-plastic", friction__displacement_limit=1e-5)).summary
    for s in (a, b):
        dT = s["spans"]["driver-driven"]["tension_mean"] - s["spans"]["driven-driver"]["tension_mean"]
        assert dT == pytest.approx(5.0 / 0.027, rel=0.03)
    # micro-slip of 10 um barely changes the creep
    assert b["pulleys"]["driven"]["slip"] == pytest.approx(a["pulleys"]["driven"]["slip"], abs=5e-4)


def test_load_laws_closed_form():
    # constant, viscous, two harmonics of the angle, bearing drag (Coulomb beyond 1 rad/s), a pump's
    # c omega |omega| and an alternator's P / (eta omega) (none below the 2 rad/s cut-in, full from 4)
    off = np.array([0, 0], dtype=np.int64)
    e = np.zeros(0)
    one = np.ones(1)
    P = BK.Pulleys(nk=1, cx=0 * one, cy=0 * one, r=one, inertia=one, inv_i=one, mode=np.zeros(1, dtype=np.int64),
                  tq_const=np.array([2.0]), tq_visc=np.array([0.1]), tt_off=off, tt_x=e, tt_y=e, ts_off=off,
                  ts_x=e, ts_y=e, hm_off=np.array([0, 2], dtype=np.int64), hm_order=np.array([2.0, 4.0]),
                  hm_amp=np.array([3.0, 1.0]), hm_phase=np.array([0.0, 0.5]), sp_off=off, sp_x=e, sp_y=e,
                  tq_drag=np.array([0.3]), w_drag=one, tq_quad=np.array([0.01]), tq_pow=np.array([100.0]),
                  w_cut=np.array([2.0]), so_off=off, so_order=e, so_amp=e, so_ang=e, so_phase=e,
                  cl_kind=np.zeros(1, dtype=np.int64), cl_ir=one, cl_k=0 * one, cl_c=0 * one, cl_s=one)
    M = BK.external_torque(P, 0, 0.3, 1.2, 5.0)
    assert M == pytest.approx(2.0 - 0.1 * 5.0 + 3 * math.sin(2 * 1.2) + math.sin(4 * 1.2 + 0.5)
                              - 0.3 - 0.01 * 25 - 100 / 5.0)
    M = BK.external_torque(P, 0, 0.3, 0.0, -0.5)
    assert M == pytest.approx(2.0 + 0.05 + 0.3 * 0.5 + 0.01 * 0.25 + math.sin(0.5))
    M = BK.external_torque(P, 0, 0.3, 0.0, 3.0)      # half the power at 1.5 x cut-in
    assert M == pytest.approx(2.0 - 0.3 + 3 * 0.0 - 0.3 - 0.09 - 50 / 3.0 + math.sin(0.5))


def test_table_interpolation_and_extrapolation():
    from drivedyn.core.tables import table

    xs, ys = np.array([0.0, 1.0, 3.0]), np.array([0.0, 2.0, 0.0])
    assert table(xs, ys, 0, 3, 0.5, False) == 1.0
    assert table(xs, ys, 0, 3, 2.0, False) == 1.0
    assert table(xs, ys, 0, 3, 5.0, False) == 0.0          # held
    assert table(xs, ys, 0, 3, 5.0, True) == -2.0          # extrapolated
