"""Planetary stage (drivedyn.gears.planetary.stage): modes against the closed forms of the lumped torsional
model (the rotational part of Lin & Parker 1999), mesh phasing against the counting rule, and load
sharing with a planet position error against the closed form."""
import math

import numpy as np
import pytest

from drivedyn.gears.planetary import stage as pl

from .conftest import assert_one_line_refusal


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


def test_planetary_model_file_run_and_check(tmp_path):
    import drivedyn
    from drivedyn.front.cli import main

    path = drivedyn.example_path("gears-planetary")
    m = drivedyn.load(path)
    assert drivedyn.loads(drivedyn.dumps(m)) == m
    r = drivedyn.run(m)
    s = r.summary["planetary"]
    assert r.status == "success"
    assert s["ring_teeth"] == 71 and s["phase_sun_planet"] == pytest.approx([0, 0.25, 0.5, 0.75])
    assert s["mode_types"].count("planet") == 3
    assert [f for f, k in zip(s["natural_frequencies_hz"], s["mode_types"]) if k == "planet"] == pytest.approx(
        [s["planet_mode_frequency_closed_form_hz"]] * 3, rel=1e-10)
    # sun in, ring fixed, carrier out: 1 + z_r / z_s
    assert s["speed_ratio_input_over_output"] == pytest.approx(1 + 71 / 25)
    # the pin error -10 um on planet 1 (ring and carrier held, 500 N m on the sun): closed form
    st = pl.stage_of(m.planetary, support={"ring": "fixed", "carrier": "fixed"})
    rbs = st.radii[0]
    ke = 5e8 * 7e8 / 12e8
    e = np.array([-10e-6, 0, 0, 0])
    expect = 500 / (4 * rbs) + ke * 2 * math.cos(math.radians(20)) * (e.mean() - e)
    assert s["sun_planet_force"] == pytest.approx(expect, rel=1e-9)
    assert r.units["planetary.sun_planet_force"] == "N"
    assert "planet modes by the closed form" in drivedyn.check(path)
    out = tmp_path / "o"
    assert main(["run", str(path), "-o", str(out), "-q"]) == 0
    assert (out / "gears-planetary.png").exists() and (out / "report.html").exists()
    # a larger pin error unloads the other planets below zero: tooth-separation, named
    r2 = drivedyn.run(drivedyn.replace(m, {"planetary.position_errors": [-60e-6, 0.0, 0.0, 0.0]}))
    # (the static load sharing's, and the time integration's: its mesh forces go below zero too)
    assert r2.status == "warning" and [d.code for d in r2.diagnostics] == ["tooth-separation"] * 2
    assert "time integration" in r2.diagnostics[1].text and r2.summary["planetary"]["dynamics"]["force_min_sun_planet"][1] < 0


@pytest.mark.parametrize("edit, expect", [
    (("planets = 4", "planets = 5"), "5 planets cannot be equally spaced"),
    (("planets = 4", "planets = 4\nplanet_angles = [0.0, 1.0]"), "planet_angles: 2 angles for 4 planets"),
    (("planets = 4", 'planets = 4\nplanet_angles = ["0 deg", "10 deg", "180 deg", "270 deg"]'), "neighbouring planets overlap"),
    (('position_errors = ["-10 um", 0.0, 0.0, 0.0]', "position_errors = [0, 0, 0, 0, 0]"), "position_errors: 5 values"),
    (('position_errors = ["-10 um", 0.0, 0.0, 0.0]', 'position_errors = ["5 mm"]'), "above one module"),
    (('input = "sun"', 'input = "ring"'), "input and fixed are both 'ring'"),
    (("planets = 4", "planets = 0"), "planetary.planets: must lie in 1..24"),
    (("sun_teeth = 25", "sun_teeth = 3"), "planetary.sun_teeth"),
    (('torque = "500 N*m"', 'torque = "-5 N*m"'), "planetary.torque"),
    (('fixed = "ring"', 'fixed = "moon"'), "planetary.fixed"),
    (('sun_planet_stiffness = "5e8 N/m"', 'sun_planet_stiffness = "0 N/m"'), "planetary.sun_planet_stiffness"),
    (('planet_mass = "0.9 kg"', ''), "planetary.planet_mass"),
])
def test_planetary_bad_input_one_line_exit_2(tmp_path, capsys, edit, expect):
    assert_one_line_refusal("gears-planetary", edit, expect, tmp_path, capsys)


def test_load_sharing_is_judged_and_said():
    """The planetary example's K_gamma (2.16: one planet carries 54 % with the sun held and a 10 um pin
    error) fails its criteria.load_sharing_max; without a limit the verdict's note says it (it read
    "not judged" with nothing about the planets)."""
    import drivedyn

    m = drivedyn.load(drivedyn.example_path("gears-planetary"))
    c = drivedyn.run(m).summary["criteria"]["load_sharing_planetary"]
    assert c["value"] == pytest.approx(2.159, abs=1e-3) and not c["pass"] and "54 %" in c["where"]
    s = drivedyn.run(drivedyn.replace(m, {"criteria.load_sharing_max": None})).summary
    assert "K_gamma 2.16" in s["criteria_skipped"]["load_sharing_planetary"]


def test_the_planetary_table_reads_in_engineering_units(tmp_path, capsys):
    """``drivedyn run`` prints the planetary stage with names a person reads, angles in degrees,
    the centre distance in mm, pin errors in um and load shares in % (it printed raw summary keys,
    angles in rad and pin errors in m)."""
    import re

    from drivedyn.front.cli import main

    assert main(["run", "examples/gears-planetary.toml", "-o", str(tmp_path), "-q", "--no-plots", "--no-report"]) == 0
    text = capsys.readouterr().out
    rows = {m.group(1).strip(): (m.group(2).strip(), m.group(3).strip())
            for m in re.finditer(r"│ ([a-zA-Z][^│]*?) +│ ([^│]+?) +│ ([^│]*?) *│", text)}
    assert rows["planet angles"] == ("[0, 90, 180, 270]", "deg")
    assert rows["centre distance"] == ("72", "mm")
    assert rows["position errors"] == ("[-10, 0, 0, 0]", "um")
    assert rows["load share"] == ("[53.97, 15.34, 15.34, 15.34]", "%")
    assert "planet_angles" not in text and "pin_error" not in text
