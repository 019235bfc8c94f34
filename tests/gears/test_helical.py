"""Helical meshes: geometry and ISO 6336-1 stiffness against ISO/TR 6336-30 example 1, the thin-slice
mesh stiffness against its closed-form properties, the axial force, and K_v against ISO method B."""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.gears.rating import mesh as rating
from drivedyn.gears.mesh import stiffness
from drivedyn.gears.train.system import assemble
from drivedyn.core.model import from_dict


def tr_pair(**changes):
    """ISO/TR 6336-30 example 1 as a gear train: z 17/103, m_n 8 mm, beta 15.8 deg, b 100 mm,
    x 0.145/0, a_w 500 mm, rack h_fP 1.4, rho_fP 0.39, T1 9000 N m at 360 rpm. Inertias of solid
    steel blanks (0.5 m r^2 over the reference radius, 7850 kg/m^3): assumed, the TR has none."""
    def j(z):
        r = 0.5 * z * 8e-3 / math.cos(math.radians(15.8))
        return 0.5 * 7850 * math.pi * r ** 2 * 0.1 * r ** 2
    data = {
        "kind": "gear-train",
        "gears": [
            {"name": "p", "teeth": 17, "module": 8e-3, "profile_shift": 0.145, "face_width": 0.1, "helix_angle": "15.8 deg",
             "hand": "left", "dedendum": 1.4, "root_radius": 0.39, "inertia": j(17)},
            {"name": "w", "teeth": 103, "module": 8e-3, "profile_shift": 0.0, "face_width": 0.1, "helix_angle": "15.8 deg",
             "hand": "right", "dedendum": 1.4, "root_radius": 0.39, "inertia": j(103), "load_fraction": 1.0},
        ],
        "meshes": [{"name": "m", "gears": ["p", "w"], "damping_ratio": 0.05, "center_distance": 0.5}],
        "drive": {"input": "p", "speed": "360 rpm", "torque": "9000 N*m"},
        "simulation": {"duration": 0.05, "step": 2e-5},
        "iso": {"life": "50000 h", "lubricant_viscosity": "320 mm^2/s", "pitch_deviation": "5 um",
                "profile_deviation": "5 um"},
    }
    from drivedyn.core.model import set_path

    for k, v in changes.items():
        set_path(data, k, v)
    return from_dict(data)


def test_helical_geometry_and_iso_stiffness_against_tr_6336_30():
    s = assemble(tr_pair())
    p = s.pairs[0]
    # transverse contact ratio: the TR's c_gamma_alpha / c' implies 1.54909; the rack's tips give 1.54934
    assert p.contact_ratio == pytest.approx((17.46485 / 12.37047 - 0.25) / 0.75, rel=2e-4)
    # the same from the rating's independent transverse formulas
    d1 = 17 * 8 / math.cos(math.radians(15.8))
    g = rating.geometry(rating.Pair(17, 103, 8.0, math.radians(20), math.radians(15.8), 0.145, 0.0, 100.0,
                                    2e3 * p.g1.ra, 2e3 * p.g2.ra, 500.0))
    assert p.contact_ratio == pytest.approx(g["eps_alpha"], rel=1e-12)
    assert 2e3 * p.g1.r == pytest.approx(d1, rel=1e-12)
    assert p.overlap_ratio == pytest.approx(100 * math.sin(math.radians(15.8)) / (math.pi * 8), rel=1e-12)   # 1.0834
    assert p.total_contact_ratio == pytest.approx(p.contact_ratio + 1.08337, abs=1e-5)
    # ISO 6336-1 c' with z_n and cos(beta): 12.37047 N/(mm um) (TR); load 1273 N/mm: no low-load factor
    iso = s.iso[0]
    assert iso.load_per_width > 100 and iso.low_load_factor == 1.0
    assert iso.c_th == pytest.approx(17.85584, abs=5e-5)
    assert iso.c_single == pytest.approx(12.37047, abs=5e-5)
    assert iso.c_gamma == pytest.approx(17.46485, rel=2e-4)


def test_slice_mean_closed_forms():
    n = 4096
    u = np.arange(n) / n
    k = np.where(u < 0.5, 1.75, 1.0)                     # a rectangular single/double wave
    for eb in (0.3, 0.77, 1.0, 2.0, 1.4):
        h = stiffness.slice_mean(k, eb)
        assert h.mean() == pytest.approx(k.mean(), rel=1e-12)          # the mean is kept
    # a whole overlap ratio spreads every contact over whole periods: constant stiffness
    for eb in (1.0, 2.0):
        h = stiffness.slice_mean(k, eb)
        assert np.ptp(h) < 1e-9 * h.mean()
    # against N discrete slices (each a shifted copy of the table): converges to the thin-slice limit
    eb = 0.77
    exact = stiffness.slice_mean(k, eb)
    errs = []
    for N in (16, 64, 256):
        shifts = ((np.arange(N) + 0.5) / N * eb * n).round().astype(int)
        disc = np.mean([np.roll(k, -sh) for sh in shifts], axis=0)
        errs.append(np.abs(disc - exact).max())
    assert errs[2] < errs[1] < errs[0] and errs[2] < 0.02 * k.mean()
    # the running mean of a square wave (levels 1 and 1.75, duty 1/2) over half its period is a triangle
    # wave between the two levels: peak to peak 0.75, values at the quarter points 1.375
    h = stiffness.slice_mean(k, 0.5)
    assert np.ptp(h) == pytest.approx(0.75, rel=2e-3)
    tri = 1.0 + 0.75 * np.abs(1 - 2 * u)                        # the triangle, peak at u = 0
    assert np.abs(h - tri).max() < 0.02


def test_helical_mesh_table_is_smoother_and_keeps_its_mean():
    spur = assemble(tr_pair(**{"gears.0.helix_angle": 0.0, "gears.1.helix_angle": 0.0, "meshes.0.center_distance": None}))
    hel = assemble(tr_pair())
    ks, kh = spur.tables[0].stiffness, hel.tables[0].stiffness
    assert np.ptp(kh) / kh.mean() < 0.25 * np.ptp(ks) / ks.mean()
    # Cai's table is normalised to ISO's c_gamma b: the slice mean keeps it
    assert hel.tables[0].mean == pytest.approx(hel.iso[0].si(0.1)[1], rel=1e-9)


def test_helical_run_axial_force_and_kv_against_iso_method_b():
    r = drivedyn.run(tr_pair())
    s = r.summary["meshes"]["m"]
    beta_b = math.atan(math.tan(math.radians(15.8)) * math.cos(math.atan(math.tan(math.radians(20)) / math.cos(math.radians(15.8)))))
    assert s["axial_force_nominal"] == pytest.approx(s["force_nominal"] * math.tan(beta_b), rel=1e-12)
    # the nominal axial force is F_t tan(beta) with F_t = 2 T1 / d1 = 127 352 N (TR): 36 030 N
    assert s["axial_force_nominal"] == pytest.approx(127352.0 * math.tan(math.radians(15.8)), rel=2e-3)
    assert s["axial_force_max"] == pytest.approx(s["kv"] * s["axial_force_nominal"], rel=1e-12)
    assert r.ds.axial_force.attrs["units"] == "N"
    # K_v: the model has no pitch or profile deviations, ISO method B adds them (5 um, grade ~5);
    # subcritical (N ~ 0.05): the simulated K_v lies between 1 and ISO's
    assert s["iso_region"] == "subcritical"
    assert 1.0 <= s["kv"] <= s["kv_iso_method_b"]
    assert r.summary["rating"]["m"]["kv_dynamic"] == s["kv"]
