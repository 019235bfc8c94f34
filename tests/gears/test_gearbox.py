"""A gearbox of stages in series (drivedyn.gears.planetary.gearbox, examples/gears-gearbox.toml): the planetary
stage's rating, lateral-torsional load sharing and modes through the model file, the whole train's
modes against the stage's and the train's own ones, the verdict over every mesh, and bad input."""
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.gears.planetary import lateral as pl
from drivedyn.gears.planetary.gearbox import modes as gearbox_modes
from drivedyn.gears.planetary.gearbox import stage_matrices
from drivedyn.gears.train.system import assemble

from .conftest import assert_one_line_refusal
from .test_planetary_rating import CASE, RING, nrel_stage


@pytest.fixture(scope="module")
def gearbox():
    m = drivedyn.load(drivedyn.example_path("gears-gearbox"))
    return m, drivedyn.run(m)


def test_gearbox_example_runs_and_judges_every_mesh(gearbox):
    m, r = gearbox
    assert drivedyn.loads(drivedyn.dumps(m)) == m
    assert r.status == "success" and r.summary["verdict"] == "fail"
    s = r.summary
    names = list(s["criteria"])
    for stage in ("planetary", "stage2"):
        for mesh in ("sun-planet", "ring-planet"):
            assert f"S_H_{stage}_{mesh}" in names and f"S_F_{stage}_{mesh}" in names
    assert "S_H_parallel" in names and "S_F_parallel" in names
    failed = [n for n, c in s["criteria"].items() if not c["pass"]]
    # the reports' own findings: stage 1's through-hardened ring flank S_H 0.96 and stage 2's sun flank
    # S_H 1.21, both below 1.25
    assert failed == ["S_H_planetary_ring-planet", "S_H_stage2_sun-planet"]
    assert s["stages"]["stage2"]["rating"]["meshes"]["sun-planet"]["sun"]["S_H"] == pytest.approx(1.21, abs=0.005)
    ring = s["planetary"]["rating"]["meshes"]["ring-planet"]["ring"]
    assert ring["S_H"] == pytest.approx(0.96, abs=0.005)
    # the rings' roots with the root sections and the yield strength (1000 N/mm^2) the reports print:
    # S_F 2.79 and 3.88 in the reports; stage 2 runs at K_v 1.06 (the report's 1.0613):
    # 3.8815 x 1.0613 / 1.06 = 3.886
    assert ring["S_F"] == pytest.approx(2.79, abs=0.005)
    ring2 = s["stages"]["stage2"]["rating"]["meshes"]["ring-planet"]["ring"]
    assert ring2["S_F"] == pytest.approx(3.8815 * 1.0613 / 1.06, abs=0.001)


def test_gearbox_rating_is_the_stage_rating(gearbox):
    # the model file's [planetary.rating] gives the same numbers as planetary_rating.rate_stage with
    # the report's data (test_planetary_rating.py checks those against the report)
    from drivedyn.gears.rating import planetary as prt

    m, r = gearbox
    direct = prt.rate_stage(nrel_stage(), (CASE, CASE, RING), planets=3, torque_sun=3945990.316 * 19 / 75,
                            speed_sun_rel=12.1 * 75 / 19 - 12.1, k_gamma=1.10, kv=(1.01, 1.05), ka=1.25,
                            life_hours=175200.0, nu40=220.0, rz_flank=(4.8, 4.8, 8.0), rz_root=(20.0, 20.0, 20.0),
                            k_hbeta=(1.15, 1.15), k_halpha=(1.0, 1.0), blank_factor=0.862, s_hmin=1.25, s_fmin=1.56)
    got = r.summary["planetary"]["rating"]["meshes"]
    for mesh, gears in (("sun-planet", ("sun", "planet")), ("ring-planet", ("planet", "ring"))):
        d = direct[mesh]
        for who, g in zip(("pinion", "wheel"), gears):
            assert got[mesh][g]["S_H"] == pytest.approx(getattr(d, who)["S_H"], rel=1e-12)
            assert got[mesh][g]["sigma_H"] == pytest.approx(getattr(d, who)["sigma_H"] * 1e6, rel=1e-12)
    # without the ring's root section the direct rating leaves the ring's root unrated
    assert math.isnan(direct["ring-planet"].wheel["S_F"]) and got["ring-planet"]["ring"]["S_F"] > 0
    assert r.units["planetary.rating.meshes.sun-planet.sun.sigma_H"] == "Pa"


def test_gearbox_floating_sun_evens_out_the_pin_error(gearbox):
    # three planets and a floating sun: the sun's equilibrium alone makes the planets' forces equal
    # (test_planetary_lateral.py); the sun held on its axis, the 50 um pin error loads planet 1 more
    m, r = gearbox
    p = r.summary["planetary"]
    la = p["lateral"]
    assert la["floating_sun"] and la["load_sharing_factor"] == pytest.approx(1.0, abs=1e-9)
    assert la["mode_counts"]["translational"] % 2 == 0 and la["mode_counts"]["planet"] == 0
    assert p["load_sharing_factor"] > 1.2
    # the carrier's torque over the sun's base circle and three planets (the carrier drives: the
    # sun's torque is the carrier's times z_s / (z_s + z_r))
    rbs = 19 * 45e-3 / 2 * math.cos(math.radians(20))
    assert la["sun_planet_force"] == pytest.approx([3945990.316 * 19 / 75 / (3 * rbs)] * 3, rel=1e-9)


def test_gearbox_modes_join_the_stage_and_the_train(gearbox):
    # weak shafts decouple them: the whole train's modes are then each stage's (its output member
    # free) and the train's own, each computed on its own
    m, _ = gearbox
    weak = drivedyn.replace(m, {"planetary.output_shaft_stiffness": 1e-3, "stages.0.output_shaft_stiffness": 1e-3})
    sys_ = assemble(weak)
    gb = gearbox_modes(weak, sys_)
    from scipy.linalg import eigh

    own = []
    for spec in (weak.planetary, weak.stages[0]):
        M, K, names, g_in, g_out, kind = stage_matrices(spec)
        f_ = np.sqrt(np.clip(eigh(K, M, eigvals_only=True), 0, None)) / (2 * math.pi)
        own.append((f_[f_ > 1.0], kind))
    fs = own[0][0]
    ft, _, _ = sys_.modes()
    want = sorted([*own[0][0], *own[1][0], *ft])
    got = [f for f in gb["natural_frequencies_hz"] if f > 1.0]
    assert [k for _, k in own] == ["lateral-torsional", "torsional"]
    assert got == pytest.approx(want, rel=1e-6)
    # the stage's own elastic modes are those of planetary_lateral with the same data
    assert all(min(abs(f - x) for x in pl.modes(_lateral(weak))[0]) < 1e-6 * f for f in fs[fs > 1.0])
    # coupled through the real shaft: one mode more than the stage's elastic ones plus the train's
    # (the stage's free output rotation becomes elastic), and every mode attributed
    strong = gearbox_modes(m, assemble(m))
    assert len(strong["natural_frequencies_hz"]) == len(want) + 2        # the stages' free output rotations
    assert strong["stages"] == ["planetary", "stage2"]
    assert all(0.0 <= e <= 1.0 + 1e-9 for e in strong["stage_energy_share"])


def _lateral(model):
    from drivedyn.gears.planetary import stage as tors

    spec = model.planetary
    st = tors.stage_of(spec, support={spec.fixed: spec.lateral.support_stiffness})
    return tors.lateral_stage(spec, st, {spec.fixed: spec.lateral.support_stiffness})


@pytest.mark.parametrize("edit, expect", [
    (('torque = "162105.5481 N*m"', 'torque = "162000 N*m"'), "drive.torque: the stage delivers 162105.548 N m"),
    (('speed = "294.5394737 rpm"', 'speed = "300 rpm"'), "drive.speed: the stage turns 'wheel' at"),
    (('output_gear = "wheel"', 'output_gear = "hub"'), "stages[0].output_gear: no gear named 'hub'"),
    (('output_gear = "wheel"\n', ''), "stages[0].output_shaft_stiffness: the last stage drives no train"),
    (('output_shaft_stiffness = "2e9 N*m/rad"', 'output_gear = "wheel"'), "give output_gear and output_shaft_stiffness together"),
    (('torque = "999650.8801 N*m"', 'torque = "999000 N*m"'), "stages[0].torque: the stage before delivers 999650.88 N m"),
    (('speed = "47.76315789 rpm"', 'speed = "47 rpm"'), "stages[0].rating.speed: the stage before turns it at"),
    (('face_load_factors = [2.06, 1.15]', 'face_load_factors = [0.5, 1.15]'), "stages[0].rating.face_load_factors: must lie in [1, 10]"),
    (('ring_teeth = 56', 'ring_teeth = 30'), "ring_teeth: a ring of 30 teeth cannot hold"),
    (('centre_distance = "863 mm"', 'centre_distance = "863.01 mm"'),
     "planetary.centre_distance: 863.010000 mm is 8.679 um above the ring-planet zero-backlash centre distance"),
    (('dynamic_factors = [1.01, 1.05]', 'dynamic_factors = [0.9, 1.05]'), "planetary.rating.dynamic_factors: must lie in [1, 10]"),
    (('ring_hardness = 240', 'ring_hardness = 24'), "planetary.rating.ring_hardness: must lie in 100..700 HB"),
    (('planet_bearing_stiffness = "5e9 N/m"', 'planet_bearing_stiffness = "-5e9 N/m"'),
     "planetary.lateral.planet_bearing_stiffness"),
])
def test_gearbox_bad_input_one_line_exit_2(tmp_path, capsys, edit, expect):
    assert_one_line_refusal("gears-gearbox", edit, expect, tmp_path, capsys)


def test_lateral_contact_loss_is_a_diagnostic(tmp_path):
    # a large pin error with the sun held on its axis unloads the other planets below zero in the
    # lateral-torsional load sharing: tooth-separation (warning), named; the floating sun keeps
    # three planets in contact (the example's load sharing)
    good = drivedyn.load(drivedyn.example_path("gears-gearbox"))
    stage = good.planetary.model_copy(update={"output_gear": None, "output_shaft_stiffness": None})
    alone = good.model_copy(update={"gears": [], "meshes": [], "drive": None, "planetary": stage, "stages": []})
    ok = drivedyn.run(alone)
    assert ok.status == "success"
    bad = drivedyn.replace(alone, {"planetary.position_errors": [-2e-3, 0.0, 0.0],
                                   "planetary.lateral.sun_bearing_stiffness": 1e10})
    r = drivedyn.run(bad)
    assert r.status == "warning"
    where = {d.quantity for d in r.diagnostics if d.code == "tooth-separation"}
    assert "planetary.lateral.sun_planet_force" in where


def test_stage_alone_kgamma_and_kv_computed_when_not_given():
    # without load_sharing_factor and dynamic_factors the rating takes K_gamma from the load sharing
    # (the lateral model's) and K_v from ISO 6336-1 method B with the planetary reduced masses
    good = drivedyn.load(drivedyn.example_path("gears-gearbox"))
    rating = good.planetary.rating.model_copy(update={"load_sharing_factor": None, "dynamic_factors": None,
                                                       "steels": None})
    stage = good.planetary.model_copy(update={"output_gear": None, "output_shaft_stiffness": None, "rating": rating})
    alone = good.model_copy(update={"gears": [], "meshes": [], "drive": None, "planetary": stage, "stages": []})
    assert drivedyn.loads(drivedyn.dumps(alone)) == alone
    s = drivedyn.run(alone).summary["planetary"]
    r = s["rating"]
    assert r["K_gamma_source"] == "load sharing" and r["K_gamma"] == pytest.approx(s["lateral"]["load_sharing_factor"])
    for e in r["meshes"].values():
        assert e["K_v_source"] == "ISO 6336-1 method B" and e["K_v"] == e["K_v_method_b"] > 1.0


def test_the_overview_shows_every_stage_its_meshes_and_the_whole_trains_modes(gearbox):
    # what `drivedyn run` prints and report.html shows: each stage's quantities, the rating of every
    # gear of both its meshes (stage 1 and stage 2), its modes, and the gearbox's modes
    from drivedyn.front.overview import tables

    _, r = gearbox
    t = {x["title"]: x for x in tables(r)}
    for k, stage in ((1, "planetary"), (2, "stage2")):
        rating = t[f"stage {k}: ISO 6336 rating, method B"]
        assert [row[1] for row in rating["rows"]] == ["sun", "planet", "planet", "ring"]
        assert [row[0] for row in rating["rows"]] == ["sun-planet", "", "ring-planet", ""]
        meshes = r.summary["planetary"] if k == 1 else r.summary["stages"][stage]
        ring = meshes["rating"]["meshes"]["ring-planet"]["ring"]
        assert rating["rows"][3][3] == f"{ring['S_H']:.3f}" and rating["rows"][3][5] == f"{ring['S_F']:.3f}"
        assert f"stage {k}: modes (lumped torsional model)" in t
        rows = {row[0]: row for row in t[f"stage {k}"]["rows"]}
        assert rows["centre distance"][1:] == ["863" if k == 1 else "584", "mm"]
    assert "stage 1: modes (lateral-torsional model, floating sun)" in t
    # a stage's K_v is not from a time integration, and the overview says so
    assert r.summary["planetary"]["rating"]["K_v_note"].startswith("not from a time integration")
    assert "not from a time integration" in t["stage 2: ISO 6336 rating, method B"]["note"]
    gb = next(x for x in t.values() if x["title"].startswith("gearbox: modes of the whole train"))
    assert gb["head"][2:] == ["energy in planetary (%)", "energy in stage2 (%)", "energy in the train (%)"]
    assert gb["rows"][0][1] == f"{r.summary['gearbox']['natural_frequencies_hz'][0]:.1f}"
    # the verdict says where in words: stage 1, stage 2
    assert r.summary["criteria"]["S_H_stage2_sun-planet"]["where"] == "stage 2 sun-planet: sun"
