"""The lateral-torsional planetary model (drivedyn.gears.planetary.lateral) against Lin & Parker's
published natural frequencies, and its static load sharing with a floating sun against closed forms
derived in this file."""
import math

import numpy as np
import pytest

from drivedyn.gears.planetary import lateral as pl

# Lin & Parker, J. Vib. Acoust. 121 (1999) 316-321, table 1 (example system): masses (kg), I/r^2
# (kg), base diameters of sun, ring, planet and the diameter of the pin circle (mm), mesh and bearing
# stiffnesses (N/m), pressure angle 24.6 deg; the ring held in rotation by k_ru = 1e9 N/m, the sun
# and the carrier free to turn.
LP = dict(m={"sun": 0.4, "ring": 2.35, "carrier": 5.43, "planet": 0.66},
          I_r2={"sun": 0.39, "ring": 3.00, "carrier": 6.29, "planet": 0.61},
          d={"sun": 77.4, "ring": 275.0, "carrier": 176.8, "planet": 100.3},
          k_mesh=5e8, k_bearing=1e8, k_ru=1e9, alpha=24.6)

# Their table 2: natural frequencies (Hz) by mode class, 3 and 4 equally spaced planets
# (translational frequencies have multiplicity 2, planet frequencies N - 3).
PUBLISHED = {
    3: {"rotational": [0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3],
        "translational": [743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9], "planet": []},
    4: {"rotational": [0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1],
        "translational": [727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6], "planet": [1808.2, 5963.8, 6981.7]},
}


def lin_parker(n, **kw):
    r = {k: v * 1e-3 / 2 for k, v in LP["d"].items()}
    a = math.radians(LP["alpha"])
    args = dict(base_radius_sun=r["sun"], base_radius_planet=r["planet"], base_radius_ring=r["ring"],
                centre_distance=r["carrier"], alpha_sun=a, alpha_ring=a,
                planet_angles=tuple(2 * math.pi * i / n for i in range(n)),
                k_sun_planet=LP["k_mesh"], k_ring_planet=LP["k_mesh"], k_planet_bearing=LP["k_bearing"],
                mass=dict(LP["m"]), inertia={k: v * r[k] ** 2 for k, v in LP["I_r2"].items()},
                bearing={m: LP["k_bearing"] for m in ("sun", "ring", "carrier")},
                torsion={"ring": LP["k_ru"] * r["ring"] ** 2})
    args.update(kw)
    return pl.LateralStage(**args)


@pytest.mark.parametrize("n", [3, 4])
def test_lin_parker_published_frequencies(n):
    f, V, names, kinds = pl.modes(lin_parker(n))
    assert len(f) == 9 + 3 * n
    for cls, pub in PUBLISHED[n].items():
        mult = {"rotational": 1, "translational": 2, "planet": n - 3}[cls]
        ours = sorted(fi for fi, k in zip(f, kinds) if k == cls)
        want = sorted(x for x in pub for _ in range(mult))
        assert len(ours) == len(want), cls
        for o, w in zip(ours, want):
            assert o == pytest.approx(w, rel=1e-3, abs=1e-3), (cls, o, w)
    assert "mixed" not in kinds


def test_modes_are_mass_normalised_and_classes_hold_with_other_data():
    # 5 planets, unequal stiffnesses: still the three classes, planet modes of multiplicity N - 3 = 2
    st = lin_parker(5, k_ring_planet=8e8, k_planet_bearing=3e8)
    f, V, names, kinds = pl.modes(st)
    M, K, _ = pl.matrices(st)
    assert V.T @ M @ V == pytest.approx(np.eye(len(f)), abs=1e-9)
    assert kinds.count("planet") == 3 * 2 and kinds.count("translational") % 2 == 0 and "mixed" not in kinds
    # unequally spaced planets: no pure translational pair any more
    st = lin_parker(3, planet_angles=(0.0, 2.0, 4.3))
    assert "translational" not in pl.modes(st)[3]


def _floating_sun_closed_form(st, T, e):
    """Floating sun, rigid pins, carrier and ring held: the sun is in equilibrium under its mesh
    forces only. Mesh n of a rigid-pin planet carries F_n = k_e (d_n . s + r_bs theta - 2 e_n cos alpha)
    (sun mesh and ring mesh in series, k_e = k_sp k_rp / (k_sp + k_rp); a tangential pin error e
    shortens both meshes by e cos alpha), d_n the unit vector of line n. Sun equilibrium:
    sum F_n d_n = 0 and sum F_n r_bs = T with sum d_n d_n^T = N/2 I (N >= 3 equally spaced) give
    F_n = T / (N r_bs) + 2 k_e cos(alpha) [mean(e) - e_n + (2/N) sum_m e_m cos(psi_n - psi_m)]."""
    n = st.n
    k_e = st.k_sun_planet * st.k_ring_planet / (st.k_sun_planet + st.k_ring_planet)
    psi = np.asarray(st.planet_angles)
    c = math.cos(st.alpha_sun)
    proj = (2.0 / n) * np.cos(psi[:, None] - psi[None, :]) @ e
    return T / (n * st.base_radius_sun) + 2 * k_e * c * (e.mean() - e + proj)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_floating_sun_one_pin_error_against_closed_form(n):
    e = np.zeros(n)
    e[0] = -20e-6
    held = {"ring": "fixed", "carrier": "fixed"}
    st = lin_parker(n, k_planet_bearing=1e16, bearing={"sun": 0.0, **held}, torsion=dict(held),
                    position_errors=tuple(e))
    T = 300.0
    out = pl.load_sharing(st, T, "sun")
    want = _floating_sun_closed_form(st, T, e)
    assert out["sun_planet_force"] == pytest.approx(want, rel=2e-6)
    if n == 3:
        # three planets: the sun's two translations even the load out exactly
        assert out["load_sharing_factor"] == pytest.approx(1.0, abs=1e-6)
    # the sun held on its axis instead: the torsional model's closed form (planetary.py)
    st_h = lin_parker(n, k_planet_bearing=1e16, bearing={"sun": "fixed", **held}, torsion=dict(held),
                      position_errors=tuple(e))
    k_e = st.k_sun_planet * st.k_ring_planet / (st.k_sun_planet + st.k_ring_planet)
    held_f = T / (n * st.base_radius_sun) + 2 * k_e * math.cos(st.alpha_sun) * (e.mean() - e)
    assert pl.load_sharing(st_h, T, "sun")["sun_planet_force"] == pytest.approx(held_f, rel=2e-6)


def test_three_planets_floating_sun_share_equally_on_soft_bearings():
    # the equal sharing of three planets is sun equilibrium alone: it holds for any pin and ring stiffness
    e = (30e-6, 0.0, -5e-6)
    st = lin_parker(3, position_errors=e, bearing={"sun": 0.0, "ring": 2e8, "carrier": "fixed"},
                    torsion={"carrier": "fixed", "ring": 5e6})
    out = pl.load_sharing(st, 200.0, "sun")
    assert out["sun_planet_force"] == pytest.approx([200.0 / (3 * st.base_radius_sun)] * 3, rel=1e-9)
    assert out["sun_displacement"] != (0.0, 0.0)
    # planet equilibrium: the ring mesh carries what the sun mesh does (same base radius, no pin moment)
    assert out["ring_planet_force"] == pytest.approx(out["sun_planet_force"], rel=1e-9)


def test_rigid_pins_and_held_centre_reduce_to_the_torsional_model():
    # pins, sun, ring and carrier rigid radially: the rotations obey the purely torsional model of
    # planetary.py, whose planet modes and load sharing the lateral model must then reproduce
    n = 4
    st = lin_parker(n, k_planet_bearing=1e15, bearing={m: "fixed" for m in ("sun", "ring", "carrier")},
                    torsion={"ring": "fixed"})
    f, V, names, kinds = pl.modes(st)
    low = sorted(f[f < 1e5])                 # the pins' own modes lie far above (k_p = 1e15 N/m)
    assert len(low) == 2 + n
    assert low == pytest.approx(sorted(_torsional_freqs(st)), rel=1e-5, abs=1e-2)
    # load sharing with one pin error: the torsional closed form of planetary.py
    e = np.array([25e-6, 0.0, 0.0, 0.0])
    st = lin_parker(n, k_planet_bearing=1e16, bearing={m: "fixed" for m in ("sun", "ring", "carrier")},
                    torsion={"ring": "fixed", "carrier": "fixed"}, position_errors=tuple(e))
    k_e = st.k_sun_planet * st.k_ring_planet / (st.k_sun_planet + st.k_ring_planet)
    want = 100.0 / (n * st.base_radius_sun) + 2 * k_e * math.cos(st.alpha_sun) * (e.mean() - e)
    assert pl.load_sharing(st, 100.0, "sun")["sun_planet_force"] == pytest.approx(want, rel=1e-6)


def _torsional_freqs(st):
    """The torsional model (rotations of sun, carrier, planets; ring held; rigid pins) written out:
    d_sn = r_bs th_s + r_bp th_n - (r_bs + r_bp) th_c is what rigid pins give (eta_n = R th_c)."""
    from scipy.linalg import eigh

    n = st.n
    c = math.cos(st.alpha_sun)
    rbs, rbp, R = st.base_radius_sun, st.base_radius_planet, st.centre_distance
    size = 2 + n
    K = np.zeros((size, size))
    for i in range(n):
        a = np.zeros(size)
        a[0], a[1], a[2 + i] = rbs, -R * c, rbp
        b = np.zeros(size)
        b[1], b[2 + i] = -R * c, -rbp
        K += st.k_sun_planet * np.outer(a, a) + st.k_ring_planet * np.outer(b, b)
    M = np.diag([st.inertia["sun"], st.inertia["carrier"] + n * st.mass["planet"] * R ** 2,
                 *([st.inertia["planet"]] * n)])
    w2 = eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(w2, 0, None)) / (2 * math.pi)


def test_unheld_stage_is_refused():
    st = lin_parker(3, torsion={})
    with pytest.raises(ValueError, match="not held"):
        pl.load_sharing(st, 100.0, "sun")
