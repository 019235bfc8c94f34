"""Planetary stage (drivedyn.gears.planetary): modes against the closed forms of the lumped torsional
model (the rotational part of Lin & Parker 1999), mesh phasing against the counting rule, and load
sharing with a planet position error against the closed form."""
import math

import numpy as np
import pytest

from drivedyn.gears import planetary as pl


def stage(n=4, z_s=24, z_p=24, **kw):
    m = 3e-3
    args = dict(z_sun=z_s, z_planet=z_p, module=m, planet_angles=tuple(2 * math.pi * i / n for i in range(n)),
                k_sun_planet=5e8, k_ring_planet=7e8, inertia_sun=0.02, inertia_ring=1.5, inertia_carrier=0.8,
                inertia_planet=0.01, mass_planet=1.2, support={"ring": "fixed"})
    args.update(kw)
    return pl.Stage(**args)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_planet_modes_closed_form(n):
    st = stage(n=n)
    f, V, names, kinds = pl.modes(st)
    rbs, rbp, rbr, R = st.radii
    f_planet = math.sqrt(rbp ** 2 * (st.k_sun_planet + st.k_ring_planet) / st.inertia_planet) / (2 * math.pi)
    planet = [fi for fi, k in zip(f, kinds) if k == "planet"]
    assert len(planet) == n - 1                                  # multiplicity N - 1
    assert planet == pytest.approx([f_planet] * (n - 1), rel=1e-10)
    assert kinds.count("mixed") == 0


@pytest.mark.parametrize("n", [3, 4, 6])
def test_rotational_modes_are_those_of_the_reduced_model(n):
    # all planets alike: one planet carrying N times the stiffness and inertia (and N m_p R^2 on the carrier)
    st = stage(n=n, support={"ring": "fixed", "carrier": 2e5})
    f, V, names, kinds = pl.modes(st)
    rot = sorted(fi for fi, k in zip(f, kinds) if k == "rotational")
    one = pl.Stage(**{**st.__dict__, "planet_angles": (0.0,), "k_sun_planet": n * st.k_sun_planet,
                      "k_ring_planet": n * st.k_ring_planet, "inertia_planet": n * st.inertia_planet,
                      "mass_planet": n * st.mass_planet})
    f1, _, _, _ = pl.modes(one)
    assert len(rot) == len(f1) == 3                               # sun, carrier, planets in phase
    assert rot == pytest.approx(sorted(f1), rel=1e-9)
    assert len(f) == 3 + n - 1


def test_free_stage_has_two_rigid_body_modes_obeying_willis():
    # sun, ring and carrier all free: a planetary stage is a two-degree-of-freedom mechanism
    st = stage(support={})
    f, V, names, kinds = pl.modes(st)
    assert f[:2] == pytest.approx([0.0, 0.0], abs=1e-6 * f[2]) and f[2] > 1.0
    # both turn the members at the stage's kinematic ratios (Willis): w_s - w_c = -(z_r / z_s)(w_r - w_c),
    # planets relative to the carrier at -(z_s / z_p)(w_s - w_c)
    for r in (0, 1):
        v = V[:, r]
        ws, wr, wc = (v[names.index(k)] for k in ("sun", "ring", "carrier"))
        wp = v[names.index("planet1")]
        scale = np.abs(v).max()
        assert (ws - wc) == pytest.approx(-(st.z_ring / st.z_sun) * (wr - wc), abs=1e-9 * scale)
        assert (wp - wc) == pytest.approx(-(st.z_sun / st.z_planet) * (ws - wc), abs=1e-9 * scale)


def test_phasing_counting_rule():
    # z_s 24, 4 planets 90 deg apart: 24 x 1/4 = 6 whole teeth: in phase
    g_s, g_r = pl.phases(stage(n=4, z_s=24, z_p=24))
    assert np.allclose(g_s, 0) and np.allclose(g_r, 0)
    # z_s 25, z_p 23 (z_r 71, z_s + z_r = 96 = 4 x 24: assembles): sequential, quarter periods
    st = stage(n=4, z_s=25, z_p=23)
    assert pl.assembly_ok(st.z_sun, st.z_ring, 4)
    g_s, g_r = pl.phases(st)
    assert g_s == pytest.approx([0.0, 0.25, 0.5, 0.75])
    assert g_r == pytest.approx([0.0, 0.25, 0.5, 0.75])          # -71/4 = -17.75 -> 0.25, ...
    # counted directly: the sun tooth nearest each planet's mesh, in pitches, as the sun turns
    pitch = 2 * math.pi / st.z_sun
    counted = [((psi - 0.0) / pitch) % 1.0 for psi in st.planet_angles]
    assert g_s == pytest.approx(counted)
    # 3 planets on z_s 25: not equally spaced-assemblable with z_r 71 (96 / 3 = 32 does): phases thirds
    st3 = stage(n=3, z_s=25, z_p=23)
    assert pl.assembly_ok(25, 71, 3)
    assert pl.phases(st3)[0] == pytest.approx([0.0, 1 / 3, 2 / 3])
    # harmonic h of the sun's mesh forces cancels over sequentially phased planets unless h z_s / N is whole
    g_s, _ = pl.phases(st)
    for h in range(1, 9):
        total = abs(np.exp(2j * math.pi * h * g_s).sum())
        assert total == pytest.approx(4.0 if (h * 25) % 4 == 0 else 0.0, abs=1e-9)


def test_load_sharing_with_a_position_error_closed_form():
    e = (40e-6, 0.0, 0.0, 0.0)
    st = stage(n=4, position_errors=e, support={"ring": "fixed", "carrier": "fixed"})
    T = 500.0
    r = pl.load_sharing(st, T)
    rbs, rbp, rbr, R = st.radii
    ke = st.k_sun_planet * st.k_ring_planet / (st.k_sun_planet + st.k_ring_planet)
    c = math.cos(st.pressure_angle)
    expect = T / (4 * rbs) + ke * 2 * c * (np.mean(e) - np.array(e))
    assert r["sun_planet_force"] == pytest.approx(expect, rel=1e-9)
    assert r["ring_planet_force"] == pytest.approx(expect * st.k_ring_planet / st.k_ring_planet, rel=1e-9)
    assert r["sun_planet_force"].sum() * rbs == pytest.approx(T, rel=1e-12)
    # without errors the planets share equally
    r0 = pl.load_sharing(stage(n=4, support={"ring": "fixed", "carrier": "fixed"}), T)
    assert r0["load_sharing_factor"] == pytest.approx(1.0, abs=1e-12)
    assert r["load_sharing_factor"] == pytest.approx(expect.max() / expect.mean(), rel=1e-9)
    # a pin 40 um behind unloads that planet: here below zero, so its teeth would lose contact
    assert r["contact_lost"] == (expect.min() < 0)
