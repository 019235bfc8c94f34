"""Studies read in the study's units: a case named by its parameters as the study writes them
("128.6 deg, 1000 rpm", not rad and rad/s), the report's keys in engineering units over the cases,
the plots' axes likewise; a supplier report's duty rows collected by index with their units; an
outputs.summary pattern that matches nothing says what would."""
import json
import math

import numpy as np
import pytest

import drivedyn
from drivedyn.study import load_study, run_study
from drivedyn.study.cases import resolve
from drivedyn.study.collect import assemble
from drivedyn.study.design import make_design, overrides_of
from drivedyn.study.shown import case_names

AG = drivedyn.example_path("fead-ag0868")


def _clocking_ds(tmp_path, status="warning"):
    """The clocking study's Dataset from made-up records (no run): each case's kv and a helix angle
    of 0.2 rad, the first case with ``status``."""
    study = load_study(drivedyn.example_path("study-gears-clocking"))
    design = make_design(study)
    cases = resolve(study, design, overrides_of)
    records = {c.key: {"status": status if k == 0 else "success", "message": "window-not-steady" if k == 0 else "",
                       "summary": {"meshes.m12.kv": 1.0 + k / 100, "meshes.m12.helix_angle": 0.2,
                                   "gears.pinion.speed_mean": c.values["drive.speed"],
                                   "pulleys.a.centre": [0.1, 0.2 + k / 1000]},
                       "units": {"meshes.m12.kv": "1", "meshes.m12.helix_angle": "rad", "gears.pinion.speed_mean": "rad/s",
                                 "pulleys.a.centre": "m"}}
               for k, c in enumerate(cases)}
    return study, assemble(study, design, cases, records, tmp_path)


def test_the_study_keeps_the_units_it_is_written_in():
    study = load_study(drivedyn.example_path("study-gears-clocking"))
    assert study.units == {"clocking_angle": "rad", "drive.speed": "rad/s"}
    (u1, s1), (u2, s2) = study.shown["clocking_angle"], study.shown["drive.speed"]
    assert (u1, u2) == ("deg", "rpm")
    assert s1 == pytest.approx(180 / math.pi, rel=1e-12) and s2 == pytest.approx(30 / math.pi, rel=1e-12)


def test_a_case_is_named_in_the_study_units(tmp_path):
    _, ds = _clocking_ds(tmp_path)
    names = case_names(ds)
    assert names[0] == "clocking_angle = 120 deg, drive.speed = 1000 rpm", names[0]
    assert names[-1] == "clocking_angle = 137.1 deg, drive.speed = 6000 rpm", names[-1]
    assert ds["clocking_angle"].attrs["units"] == "rad"          # study.nc stays SI


def test_the_report_reads_in_the_study_and_engineering_units(tmp_path):
    from types import SimpleNamespace

    from drivedyn.front.study_report import write_study_report

    _, ds = _clocking_ds(tmp_path)
    res = SimpleNamespace(ds=ds, counts={"total": 42, "success": 41, "warning": 1}, plots=[])
    html = write_study_report(res, "study.toml", tmp_path).read_text()
    assert "warning</code>: clocking_angle = 120 deg, drive.speed = 1000 rpm: window-not-steady" in html
    assert "rad/s" not in html.split("<details>")[0] and ">rad<" not in html
    # the helix angle 0.2 rad in degrees, the pinion's speed in the study's rpm, the centre by component in mm
    assert ">11.46<" in html and ">deg<" in html
    assert ">1000<" in html and ">6000<" in html and ">rpm<" in html
    assert "centre x" in html and "centre y" in html and ">100<" in html and ">241<" in html
    # the largest kv (1 + 41/100) is the last case's
    assert "clocking_angle = 137.1 deg, drive.speed = 6000 rpm" in html
    assert "120, 122.9, 125.7, 128.6, 131.4, 134.3, 137.1" in html


def test_the_plots_read_in_the_study_units(tmp_path):
    from drivedyn.study.plots import plot_key

    _, ds = _clocking_ds(tmp_path)
    ax = plot_key(ds, "meshes.m12.helix_angle").axes[0]
    assert ax.get_xlabel() == "drive.speed (rpm)" and ax.get_ylabel() == "clocking_angle (deg)"
    assert ax.get_xlim()[1] > 5000 and ax.get_ylim()[1] < 140


def test_keys_with_spaces_are_one_word_variables(tmp_path):
    study = load_study(drivedyn.example_path("study-gears-clocking"))
    design = make_design(study)
    cases = resolve(study, design, overrides_of)
    records = {c.key: {"status": "success", "message": "", "summary": {"supplier.positions.TEN.rows.free arm.rel": 0.0}}
               for c in cases}
    ds = assemble(study, design, cases, records, tmp_path)
    var = ds["supplier.positions.TEN.rows.free_arm.rel"]
    assert var.attrs["long_name"] == "supplier.positions.TEN.rows.free arm.rel"
    assert not any(" " in str(v) for v in ds.variables)


STUDY = f"""
base = "{AG.as_posix()}"
mode = "check"
[overrides]
"duty_cycle.dynamic" = false
"duty_cycle.tolerance" = false
[[parameters]]
path = "duty_cycle.idler_drag"
values = ["5 W", "10 W"]
[outputs]
summary = ["supplier.duty.rows.*.belt_speed", "supplier.duty.rows.*.crank_speed", "supplier.pulleys.CRK.*",
           "supplier.duty.rows.*.running_arm.slip_factor.*", "supplier.duty.rows.*.slip_factor"]
"""


def test_duty_rows_are_collected_by_index_with_their_units(client, write_study, tmp_path):
    """The rows were one list value each: no pattern reached them ("matching no summary key")."""
    from drivedyn.study.collect import unmatched_lines

    res = run_study(write_study(STUDY), out=tmp_path / "out", client=client, plots=False)
    ds = res.ds
    assert (ds["status"] == "success").all(), ds["message"].values
    model = drivedyn.load(AG)
    rows = model.duty_cycle.rows
    for k, row in enumerate(rows):
        v, w = ds[f"supplier.duty.rows.{k}.belt_speed"], ds[f"supplier.duty.rows.{k}.crank_speed"]
        assert v.attrs["units"] == "m/s" and w.attrs["units"] == "rad/s"
        # the belt runs at the crank's speed on its pitch circle: v = omega d / 2
        d = ds["supplier.pulleys.CRK.pitch_diameter"].values
        assert np.allclose(v.values, w.values * d / 2, rtol=1e-9)
        assert float(w.values[0]) == pytest.approx(row.crank_speed, rel=1e-12)
    sf = ds["supplier.duty.rows.0.running_arm.slip_factor.A_C"]
    assert sf.attrs["units"] == "1" and (sf.values > 1).all()
    # the pattern without the pulley: what would match it
    (line,) = unmatched_lines(ds)
    assert line.startswith("outputs.summary: 'supplier.duty.rows.*.slip_factor' matches no summary key; near: ")
    assert "supplier.duty.rows.0.fixed_arm.slip_factor.CRK" in line and "'supplier.duty.rows.*.slip_factor.*'" in line
    assert json.loads(ds.attrs["unmatched_near"])


def test_a_misspelt_pattern_gets_the_close_keys():
    from drivedyn.study.collect import near_keys

    keys = ["pulleys.driven.slip", "pulleys.driver.slip", "spans.a-b.tension_mean"]
    assert near_keys("pulleys.drivn.slip", keys).startswith("pulleys.driven.slip")
    assert "spans.a-b.tension_mean" in near_keys("spans.a-b.tension_men", keys)
    assert near_keys("pulleys.driven", keys).startswith("pulleys.driven.slip (keys below it")
    assert near_keys("zzz.qqq", keys) == ""


def test_a_dry_run_lists_the_cases_in_the_study_units(capsys, tmp_path):
    from drivedyn.front.cli import main

    assert main(["study", str(drivedyn.example_path("study-gears-clocking")), "--dry-run", "-o", str(tmp_path / "o")]) == 0
    err = capsys.readouterr().err
    assert "clocking_angle=120 deg, drive.speed=1000 rpm" in err and "rad" not in err, err
